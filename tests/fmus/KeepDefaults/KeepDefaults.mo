model KeepDefaults "starts an exporter printed with %f: the declared 0.000000 stands for 1e-7"
  parameter Real h_min = 1e-7 "smallest internal step; declared start rounded to 0.000000";
  Modelica.Blocks.Interfaces.RealInput u(start = 1e-7) "declared start rounded to 0.000000";
  Modelica.Blocks.Interfaces.RealOutput y "1 with the model's own values";
equation
  y = u / h_min;
  assert(h_min > 0, "h_min must be positive: no internal step can finish");
end KeepDefaults;
