model BouncingBall "Ball falling on a floor at h = 0; the bounce is an internal event"
  parameter Real g(unit="m/s2") = 9.81;
  parameter Real e = 0.8 "coefficient of restitution";
  parameter Real h0(unit="m") = 1;
  parameter Real v0(unit="m/s") = 0;
  parameter Real gap_tol(unit="m") = 1e-6
    "a rebound lower than this ends with the ball at rest on the floor";
  Modelica.Blocks.Interfaces.RealOutput h(unit="m", start=h0, fixed=true);
  Modelica.Blocks.Interfaces.RealOutput v(unit="m/s", start=v0, fixed=true);
protected
  Boolean resting = h <= 0 and abs(v) <= 0;
equation
  der(h) = v;
  der(v) = if resting then 0 else -g;
  when h < 0 then
    reinit(h, 0);
    reinit(v, if (e * pre(v))^2 <= 2 * g * gap_tol then 0 else -e * pre(v));
  end when;
end BouncingBall;
