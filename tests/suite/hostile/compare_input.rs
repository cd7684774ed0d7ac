//! `compare` on images whose decoded size, not file size, is the danger, and thresholds that are not numbers.
