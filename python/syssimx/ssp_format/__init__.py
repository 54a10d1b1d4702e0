"""The SSP file format without Systems: archives and documents, what reading an SSP raises, the
default experiment, and the writer System.to_ssp calls. It stands below `system`, so that
System imports it downward; `syssimx.ssp` builds Systems from SSP files on top of it."""
