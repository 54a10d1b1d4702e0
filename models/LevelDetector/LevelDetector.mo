model LevelDetector "tank emptied when its level reaches the threshold; the output clock full ticks there"
  parameter Real threshold(unit="m") = 0.3 "level at which the tank is emptied";
  parameter Real level0(unit="m") = 0 "initial level";
  Modelica.Blocks.Interfaces.RealInput inflow(unit="m/s", start=1) "rate at which the level rises";
  Modelica.Blocks.Interfaces.RealOutput level(unit="m", start=level0, fixed=true) "level in the tank";
  Modelica.Blocks.Interfaces.RealOutput count(start=0) "how many times the tank was full";
  Clock full = Clock(level >= threshold) "ticks when the level reaches the threshold";
equation
  der(level) = inflow;
  when level >= threshold then
    reinit(level, 0);
  end when;
  count = previous(count) + 1 "clocked by full";
end LevelDetector;
