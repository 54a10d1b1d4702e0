model Terminating "y = y0 + slope * time; the model asks to end the simulation at stop_time"
  parameter Real y0 = 0;
  parameter Real slope = 1;
  parameter Real stop_time(unit="s") = 1;
  Modelica.Blocks.Interfaces.RealOutput y;
equation
  y = y0 + slope * time;
  when time >= stop_time then
    terminate("the ramp reached stop_time");
  end when;
end Terminating;
