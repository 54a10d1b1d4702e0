model Failing "y = u; after fail_time the FMU fails as `failure` chooses (tests error handling of masters)"
  parameter Real fail_time(unit="s") = 1;
  parameter Integer failure = 0 "0 doStep error, 1 doStep fatal, 2 doStep discard, 3 fmi2Get error, 4 NaN output";
  Modelica.Blocks.Interfaces.RealInput u;
  Modelica.Blocks.Interfaces.RealOutput y;
equation
  y = if failure == 4 and time > fail_time then 0.0 / 0.0 else u;
  assert(time <= fail_time, "the simulation passed fail_time");
end Failing;
