//! TEMPORARY stub (helper is writing the real file).
pub struct RootOptions {
    pub periodic: Vec<bool>,
    pub scale: f64,
    pub starts: usize,
    pub max_iter: usize,
    pub tol: f64,
    pub max_roots: usize,
}
impl Default for RootOptions {
    fn default() -> Self {
        RootOptions { periodic: Vec::new(), scale: 10.0, starts: 64, max_iter: 100, tol: 1e-10, max_roots: 32 }
    }
}
pub struct Root {
    pub x: Vec<f64>,
    pub residual: f64,
}
#[allow(clippy::type_complexity)]
pub fn find_roots(
    _f: &dyn Fn(&[f64]) -> Option<Vec<f64>>,
    _jac: &dyn Fn(&[f64]) -> Option<Vec<Vec<f64>>>,
    _opts: &RootOptions,
) -> Vec<Root> {
    Vec::new()
}
