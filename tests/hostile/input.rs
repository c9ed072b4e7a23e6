//! Hostile inputs: input.

#[allow(unused_imports)]
use crate::bound::*;
