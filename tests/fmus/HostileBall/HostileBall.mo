model HostileBall "FMUSDK's bouncing ball with its event residue; der(v) NaN from nan_time on (a test model)"
  parameter Real g(unit="m/s2") = 9.81;
  parameter Real e = 0.7 "coefficient of restitution";
  parameter Real h0(unit="m") = 1;
  parameter Real residue(unit="m") = 4e-14 "how far below the floor the bounce leaves the ball";
  parameter Real nan_time(unit="s") = -1 "from this time on der(v) is NaN (negative: never)";
  Real h(unit="m", start=h0, fixed=true);
  Real v(unit="m/s", start=0, fixed=true);
equation
  der(h) = v;
  der(v) = if nan_time >= 0 and time >= nan_time then 0.0 / 0.0 else -g;
  when h < 0 then
    reinit(v, -e * pre(v));
    reinit(h, -residue);
  end when;
end HostileBall;
