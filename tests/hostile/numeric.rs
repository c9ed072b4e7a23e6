//! Hostile inputs: numeric.

#[allow(unused_imports)]
use crate::bound::*;
