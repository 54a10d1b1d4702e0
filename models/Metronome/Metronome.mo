model Metronome "beats on a changing clock: every period, twice as fast after faster_after beats"
  parameter Real period(unit="s") = 0.2 "interval between the first beats";
  parameter Integer faster_after = 3 "beats after which the interval is halved";
  Modelica.Blocks.Interfaces.RealOutput count(start=0) "beats so far";
  Modelica.Blocks.Interfaces.RealOutput last_beat(unit="s", start=-1) "time of the last beat";
  Real interval(start=period) "interval between beats";
  Clock beat = Clock(interval) "a changing clock: its interval is announced when it changes";
equation
  when beat then
    count = previous(count) + 1;
    last_beat = sample(time, beat);
    interval = if count == faster_after then previous(interval) / 2 else previous(interval);
  end when;
end Metronome;
