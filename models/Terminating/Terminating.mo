model Terminating "y = slope * time; the model asks to end the simulation at stop_time"
  parameter Real slope = 1;
  parameter Real stop_time(unit="s") = 1;
  Modelica.Blocks.Interfaces.RealOutput y;
equation
  y = slope * time;
  when time >= stop_time then
    terminate("the ramp reached stop_time");
  end when;
end Terminating;
