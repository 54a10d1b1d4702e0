model Failing "y = u; a step that ends after fail_time fails (tests error handling of masters)"
  parameter Real fail_time(unit="s") = 1;
  Modelica.Blocks.Interfaces.RealInput u;
  Modelica.Blocks.Interfaces.RealOutput y;
equation
  y = u;
  assert(time <= fail_time, "the simulation passed fail_time");
end Failing;
