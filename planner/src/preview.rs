//! Preview SVG: the target outline, the planned tiles over it and the fold order.
