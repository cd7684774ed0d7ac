//! Names are data: control characters never reach a terminal raw or break SVG, dot or JSON.
