model TickCounter "counts the ticks of the triggered input clock tick"
  Clock tick "ticked by the importer (a triggered input clock)";
  Modelica.Blocks.Interfaces.RealInput signal "value sampled at each tick";
  Modelica.Blocks.Interfaces.RealOutput count(start=0) "ticks so far";
  Modelica.Blocks.Interfaces.RealOutput last_tick(start=-1) "time of the last tick";
  Modelica.Blocks.Interfaces.RealOutput sampled(start=0) "signal sampled at the last tick";
equation
  when tick then
    count = previous(count) + 1;
    last_tick = sample(time, tick);
    sampled = sample(signal, tick);
  end when;
end TickCounter;
