model PendulumDiscreteContact
  "Pendulum that bounces off a wall at theta_wall; the contact is an internal event"
  parameter Real m(unit="kg") = 40;
  parameter Real L(unit="m") = 0.6;
  parameter Real theta0(unit="rad") = 0;
  parameter Real omega0(unit="rad/s") = 0;
  parameter Real g(unit="m/s2") = 9.81;
  parameter Real inertia(unit="kg.m2") = 20;
  parameter Real theta_wall(unit="rad") = 0 "angle of the wall";
  parameter Integer sense = -1 "-1: the wall is hit while theta decreases, +1: while it increases";
  parameter Real restitution = 1 "omega after impact = -restitution * omega before";
  parameter Real gap_tol(unit="rad") = 1e-6
    "contact band; a rebound that would not leave it ends at rest against the wall";

  Modelica.Blocks.Interfaces.RealInput torque(unit="N.m");
  Modelica.Blocks.Interfaces.RealOutput theta(unit="rad");
  Modelica.Blocks.Interfaces.RealOutput omega(unit="rad/s");
  Modelica.Blocks.Interfaces.RealOutput alpha(unit="rad/s2");
  Modelica.Blocks.Interfaces.BooleanOutput contact "the pendulum touches the wall";

protected
  Real gap(unit="rad") = -sense * (theta - theta_wall) "positive on the free side of the wall";
  Real push(unit="rad/s2") = sense * (-(m * g * L / inertia) * sin(theta) + torque / inertia)
    "acceleration towards the wall";
  Boolean resting = gap <= 0 and abs(omega) <= 0 and push >= 0;

initial equation
  theta = theta0;
  omega = omega0;

equation
  der(theta) = if resting then 0 else omega;
  der(omega) = if resting then 0 else -(m * g * L / inertia) * sin(theta) + torque / inertia;
  alpha = der(omega);
  contact = abs(theta - theta_wall) <= gap_tol;
  when gap < 0 then
    reinit(theta, theta_wall);
    reinit(omega, if (restitution * pre(omega))^2 <= 2 * max(push, 0) * gap_tol
                  then 0 else -restitution * pre(omega));
  end when;
end PendulumDiscreteContact;
