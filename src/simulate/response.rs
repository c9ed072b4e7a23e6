//! `qdot response --over` by its former path: the sweep is
//! [`qdot_study::response`], its writers [`crate::output::response`].

pub use crate::output::response::{
    swept_csv as csv, swept_json as json, swept_text as text, ResponseSweepJson,
};
pub use qdot_study::response::*;
