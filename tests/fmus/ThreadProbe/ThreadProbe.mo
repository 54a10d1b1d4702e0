model ThreadProbe "thread = the id of the thread that last stepped the FMU; with partners > 1 a step waits until that many instances step at once, then lasts 1 ms (tests of masters that step FMUs on several threads)"
  function threadId "gettid() of the calling thread"
    output Real id;
  external "C" id = gettid();
  end threadId;
  parameter Integer partners = 0 "instances that must be stepping at once (0 or 1: no wait)";
  Modelica.Blocks.Interfaces.RealOutput thread;
equation
  thread = threadId();
end ThreadProbe;
