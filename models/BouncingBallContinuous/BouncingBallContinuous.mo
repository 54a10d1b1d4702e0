model BouncingBallContinuous
  "Free fall only: the bounce is left to the master, which re-initializes h0 and v0"
  parameter Real g(unit="m/s2") = 9.81;
  parameter Real h0(unit="m") = 1;
  parameter Real v0(unit="m/s") = 0;
  Modelica.Blocks.Interfaces.RealOutput h(unit="m", start=h0, fixed=true);
  Modelica.Blocks.Interfaces.RealOutput v(unit="m/s", start=v0, fixed=true);
equation
  der(h) = v;
  der(v) = -g;
end BouncingBallContinuous;
