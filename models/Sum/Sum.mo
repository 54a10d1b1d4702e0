model Sum "y = b - c * u"
  // The input is a length in centimetres, the output in metres: c carries the conversion,
  // its unit is m/cm (c = 0.01 weighs the input by one).
  parameter Real b(unit="m") = 0 "offset";
  parameter Real c = 1 "weight of the input, in m per cm of input";
  Modelica.Blocks.Interfaces.RealInput u(unit="cm");
  Modelica.Blocks.Interfaces.RealOutput y(unit="m");
equation
  y = b - c * u;
end Sum;
