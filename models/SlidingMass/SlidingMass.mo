model SlidingMass "Mass launched along a floor with Coulomb friction; it stops at v = 0"
  parameter Real mu = 0.3 "coefficient of friction";
  parameter Real g(unit="m/s2") = 9.81;
  parameter Real x0(unit="m") = 0;
  parameter Real v0(unit="m/s") = 2 "initial velocity (forward, > 0)";
  Modelica.Blocks.Interfaces.RealOutput x(unit="m", start=x0, fixed=true);
  Modelica.Blocks.Interfaces.RealOutput v(unit="m/s", start=v0, fixed=true);
protected
  Boolean moving = v > 0;
equation
  der(x) = v;
  der(v) = if moving then -mu * g else 0;
  when v <= 0 then
    reinit(v, 0);
  end when;
end SlidingMass;
