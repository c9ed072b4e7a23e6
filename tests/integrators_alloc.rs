//! The explicit integrators' step loop does not allocate: with a single
//! output time, the number of allocations does not grow with the number of
//! steps. (The counting allocator is global to the test crate; it counts
//! per thread, so the tests running beside this one do not disturb it.)

use qdot::simulate::{integrate, FnSystem, IntegratorOptions, Method};
use std::alloc::{GlobalAlloc, Layout, System as SysAlloc};
use std::cell::Cell;

struct Counting;

thread_local! {
    /// Allocations made by this thread (the test harness's other threads
    /// allocate concurrently).
    static ALLOCS: Cell<usize> = const { Cell::new(0) };
}

unsafe impl GlobalAlloc for Counting {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        ALLOCS.with(|c| c.set(c.get() + 1));
        unsafe { SysAlloc.alloc(layout) }
    }
    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        unsafe { SysAlloc.dealloc(ptr, layout) }
    }
}

#[global_allocator]
static GLOBAL: Counting = Counting;

fn allocations(method: Method, t_end: f64) -> (usize, usize) {
    let mut sys = FnSystem {
        dim: 2,
        f: |_t: f64, y: &[f64], dy: &mut [f64]| {
            dy[0] = y[1];
            dy[1] = -y[0].sin();
        },
    };
    let opts = IntegratorOptions {
        t_end,
        dt: (method == Method::Rk4).then_some(0.01),
        t_out: vec![t_end],
        ..IntegratorOptions::default()
    };
    let before = ALLOCS.with(Cell::get);
    let sol = integrate(&mut sys, method, &[1.0, 0.0], &opts).expect("valid");
    let after = ALLOCS.with(Cell::get);
    (after - before, sol.stats.steps)
}

#[test]
fn the_step_loop_does_not_allocate() {
    for m in [Method::Rk4, Method::Dopri5, Method::Dop853, Method::Vern7] {
        let (short, s1) = allocations(m, 1.0);
        let (long, s2) = allocations(m, 100.0);
        assert!(s2 > 20 * s1, "{m:?}: {s1} vs {s2} steps");
        assert_eq!(short, long, "{m:?}: allocations grow with the steps");
    }
}
