"""snell-farm: render snell scenes on a Ray cluster.

A job is split into tasks of one frame and one tile each; workers render their tile with
``snell render --frames F --region ...`` from a copy of the scene sent through Ray's object
store, and the driver puts each frame's tiles back together with ``snell merge``, so every
frame has the same bytes as ``snell render`` of it on one machine.
"""

__version__ = "0.1.0"
