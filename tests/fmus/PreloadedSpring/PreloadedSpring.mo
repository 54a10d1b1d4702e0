model PreloadedSpring "spring torque set from the angle input when initialization ends"
  parameter Real k(unit = "N.m/rad") = 100 "stiffness";
  parameter Real angle0(unit = "rad") = 0.1 "unloaded angle";
  Modelica.Blocks.Interfaces.RealInput angle(unit = "rad") "read when initialization ends";
  Modelica.Blocks.Interfaces.RealInput omega(unit = "rad/s") "integrated into the torque";
  Modelica.Blocks.Interfaces.RealOutput tau(unit = "N.m") "spring torque";
initial equation
  tau = -k * (angle - angle0);
equation
  der(tau) = -k * omega;
end PreloadedSpring;
