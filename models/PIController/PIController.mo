model PIController "u = kp * e + ki * integral of e, e = setpoint - measurement"
  parameter Real kp = 1 "proportional gain";
  parameter Real ki(unit="1/s") = 1 "integral gain";
  parameter Real integral0 = 0 "initial value of the integral";
  Modelica.Blocks.Interfaces.RealInput setpoint;
  Modelica.Blocks.Interfaces.RealInput measurement;
  Modelica.Blocks.Interfaces.RealOutput u;
  Real integral(start=integral0, fixed=true);
equation
  der(integral) = setpoint - measurement;
  u = kp * (setpoint - measurement) + ki * integral;
end PIController;
