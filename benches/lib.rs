//! Nothing: the benches, the reports and the examples are its targets.
