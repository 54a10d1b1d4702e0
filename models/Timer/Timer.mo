model Timer "an alarm on a countdown clock: rings after delay, then each interval growth times the last"
  parameter Real delay(unit="s") = 0.1 "interval to the first alarm";
  parameter Real growth = 2 "each interval over the one before";
  Modelica.Blocks.Interfaces.RealOutput count(start=0) "alarms so far";
  Modelica.Blocks.Interfaces.RealOutput last_alarm(unit="s", start=-1) "time of the last alarm";
  Real next_interval(start=delay) "interval to the next alarm";
  Clock alarm = Clock(next_interval) "a countdown clock: its interval is announced at each tick";
equation
  when alarm then
    count = previous(count) + 1;
    last_alarm = sample(time, alarm);
    next_interval = growth * previous(next_interval);
  end when;
end Timer;
