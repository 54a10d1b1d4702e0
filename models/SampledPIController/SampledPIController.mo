model SampledPIController "PI controller sampled every 0.1 s: u = kp * e + ki * integral"
  parameter Real kp = 1 "proportional gain";
  parameter Real ki(unit="1/s") = 1 "integral gain";
  Modelica.Blocks.Interfaces.RealInput setpoint;
  Modelica.Blocks.Interfaces.RealInput measurement;
  Modelica.Blocks.Interfaces.RealOutput u;
  Real e(start=0) "the sampled error";
  Real integral(start=0) "sum of T e over the ticks before the last";
equation
  e = sample(setpoint - measurement, Clock(0.1));
  integral = previous(integral) + interval(e) * previous(e);
  u = kp * e + ki * integral;
end SampledPIController;
