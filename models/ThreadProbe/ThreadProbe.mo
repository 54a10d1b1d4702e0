model ThreadProbe "thread = the id of the thread that last stepped the FMU (tests of masters that step FMUs on several threads)"
  function threadId "gettid() of the calling thread"
    output Real id;
  external "C" id = gettid();
  end threadId;
  Modelica.Blocks.Interfaces.RealOutput thread;
equation
  thread = threadId();
end ThreadProbe;
