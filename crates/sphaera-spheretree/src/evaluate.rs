//! Fit evaluation of sphere sets (work in progress).
