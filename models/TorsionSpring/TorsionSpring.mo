model TorsionSpring "Spring-damper between two rotating bodies; pure feedthrough"
  parameter Real k(unit="N.m/rad") = 100 "stiffness";
  parameter Real d(unit="N.m.s/rad") = 1 "damping";
  Modelica.Blocks.Interfaces.RealInput theta1(unit="rad");
  Modelica.Blocks.Interfaces.RealInput theta2(unit="rad");
  Modelica.Blocks.Interfaces.RealInput omega1(unit="rad/s");
  Modelica.Blocks.Interfaces.RealInput omega2(unit="rad/s");
  Modelica.Blocks.Interfaces.RealOutput tau1(unit="N.m") "torque on body 1";
  Modelica.Blocks.Interfaces.RealOutput tau2(unit="N.m") "torque on body 2";
equation
  tau1 = -k * (theta1 - theta2) - d * (omega1 - omega2);
  tau2 = -tau1;
end TorsionSpring;
