//! Hostile inputs: mechanics.

#[allow(unused_imports)]
use crate::bound::*;
