model SampledSignal "x decays continuously; y samples x every 0.1 s and holds it"
  parameter Real x0 = 1 "x at the start time";
  parameter Real tau(unit="s") = 0.5 "time constant of the decay";
  Modelica.Blocks.Interfaces.RealOutput x(start=x0, fixed=true);
  Modelica.Blocks.Interfaces.RealOutput y(start=0) "x at the last tick";
  Modelica.Blocks.Interfaces.RealOutput ticks(start=0) "how many times the clock ticked";
equation
  der(x) = -x / tau;
  y = sample(x, Clock(0.1));
  ticks = previous(ticks) + 1;
end SampledSignal;
