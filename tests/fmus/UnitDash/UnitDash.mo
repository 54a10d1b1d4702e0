model UnitDash "y = k * u with the unit \"-\" (dimensionless, as Parker and Hopsan export it)"
  parameter Real k(unit = "-") = 2;
  Modelica.Blocks.Interfaces.RealInput u(unit = "-");
  Modelica.Blocks.Interfaces.RealOutput y(unit = "-");
equation
  y = k * u;
end UnitDash;
