"""Pictures of systems (``system_graph_visualizer``, needs Graphviz) and plots of results
(``plot``, matplotlib). Import the submodule you need; neither is loaded by ``syssimx``."""
