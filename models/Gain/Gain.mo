model Gain "y = k * u"
  parameter Real k = 1;
  Modelica.Blocks.Interfaces.RealInput u(unit="m");
  Modelica.Blocks.Interfaces.RealOutput y(unit="m");
equation
  y = k * u;
end Gain;
