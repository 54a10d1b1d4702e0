model LateNaN "a ramp and an output that turns NaN at nan_time"
  parameter Real nan_time(unit = "s") = 0.5 "limit is NaN from this time on";
  Modelica.Blocks.Interfaces.RealOutput y "the ramp y = t";
  Modelica.Blocks.Interfaces.RealOutput limit "1, NaN from nan_time on";
equation
  y = time;
  limit = if time >= nan_time then 0 / 0 else 1;
end LateNaN;
