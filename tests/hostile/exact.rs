//! Hostile inputs: exact.

#[allow(unused_imports)]
use crate::bound::*;
