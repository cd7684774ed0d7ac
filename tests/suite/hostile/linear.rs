//! Work that must stay linear (or n log n) in the rays and marks of a big ray tree.
