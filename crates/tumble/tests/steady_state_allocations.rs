//! A steady-state step allocates nothing: a resting pyramid, a pile of ragdolls and a pile of
//! hulls on a terrain mesh (sleep off, so every body, contact and joint is still processed each
//! step) and a swinging chain are stepped
//! until their contacts and pairs stop changing, then the heap allocations of further steps are counted by a global allocator
//! that counts (one per test binary, hence this file of its own).

use std::alloc::{GlobalAlloc, Layout, System};
use std::sync::atomic::{AtomicUsize, Ordering};

use tumble::scenes;

struct Counting;

static ALLOCATIONS: AtomicUsize = AtomicUsize::new(0);

// SAFETY: forwards to the system allocator unchanged; only counts the calls.
#[allow(unsafe_code)]
unsafe impl GlobalAlloc for Counting {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        ALLOCATIONS.fetch_add(1, Ordering::Relaxed);
        System.alloc(layout)
    }
    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        System.dealloc(ptr, layout)
    }
    unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        ALLOCATIONS.fetch_add(1, Ordering::Relaxed);
        System.realloc(ptr, layout, new_size)
    }
}

#[global_allocator]
static GLOBAL: Counting = Counting;

/// Allocations made by `steps` more steps of the scene after `warm_up` steps.
fn allocations(name: &str, size: usize, warm_up: u32, steps: u32) -> usize {
    let mut scene = scenes::by_name(name, Some(size)).expect("a known scene");
    let sleep = tumble::SleepSettings { enabled: false, ..scene.world.sleep_settings().clone() };
    scene.world.set_sleep_settings(sleep);
    for _ in 0..warm_up {
        scene.world.step(scene.dt).expect("valid step");
    }
    let before = ALLOCATIONS.load(Ordering::Relaxed);
    for _ in 0..steps {
        scene.world.step(scene.dt).expect("valid step");
    }
    ALLOCATIONS.load(Ordering::Relaxed) - before
}

// The tests run one after the other: a second test thread allocating would be counted too.
#[test]
fn steady_state_steps_do_not_allocate() {
    let pyramid = allocations("pyramid", 10, 300, 100);
    let chain = allocations("chain", 10, 600, 100);
    // The ragdolls go on making and breaking a few contacts for 10 s; the contact store last grows
    // (to its largest number of contacts) after 625 steps.
    let ragdolls = allocations("ragdolls", 4, 900, 100);
    // Hulls on a triangle-mesh terrain and on each other: the separating-axis test, the mesh's
    // triangles, GJK and EPA.
    let convex_pile = allocations("convex_pile", 30, 300, 100);
    assert_eq!(
        (pyramid, chain, ragdolls, convex_pile),
        (0, 0, 0, 0),
        "allocations in 100 steady-state steps of (pyramid, chain, ragdolls, convex_pile)"
    );
}
