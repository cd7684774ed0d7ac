//! Outputs aimed at inputs, inputs that are not regular files, and readers past their size caps.
