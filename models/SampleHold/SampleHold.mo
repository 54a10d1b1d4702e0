model SampleHold "A cosine sampled every hold_step and held in between"
  import Modelica.Constants.pi;
  parameter Real amplitude = 1;
  parameter Real f(unit="1/s") = 0.7;
  parameter Real hold_step(unit="s") = 1e-3;
  Modelica.Blocks.Interfaces.RealOutput y;
equation
  when sample(0, hold_step) then
    y = amplitude * cos(2 * pi * f * time);
  end when;
end SampleHold;
