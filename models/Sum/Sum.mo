model Sum "y = b - c * u"
  parameter Real b = 0 "offset";
  parameter Real c = 1 "weight of the input";
  Modelica.Blocks.Interfaces.RealInput u;
  Modelica.Blocks.Interfaces.RealOutput y;
equation
  y = b - c * u;
end Sum;
