//! Threads change nothing: the shared `pyramid`, `ragdolls` and `rain` scenes stepped 300 times
//! give the same `state_hash` on 1, 2 and 4 threads, and again on a second run. (The pyramid's and
//! the rain's large colours are split between the threads, dynamics/colouring.rs.)

use tumble::scenes;

fn hash_after(name: &str, size: usize, threads: usize, steps: u32) -> u64 {
    let mut scene = scenes::by_name(name, Some(size)).expect("a known scene");
    scene.world.set_threads(threads).expect("threads start");
    assert_eq!(scene.world.threads(), threads.max(1));
    for _ in 0..steps {
        scene.world.step(scene.dt).expect("valid step");
    }
    scene.world.state_hash()
}

fn check(name: &str, size: usize) {
    check_steps(name, size, 300);
}

fn check_steps(name: &str, size: usize, steps: u32) {
    let reference = hash_after(name, size, 1, steps);
    for threads in [1, 2, 4] {
        assert_eq!(hash_after(name, size, threads, steps), reference, "{name} on {threads} threads");
    }
}

#[test]
fn pyramid_state_hash_is_the_same_on_any_thread_count() {
    check("pyramid", 20);
}

#[test]
fn ragdolls_state_hash_is_the_same_on_any_thread_count() {
    check("ragdolls", 20);
}

#[test]
fn rain_state_hash_is_the_same_on_any_thread_count() {
    check_steps("rain", 400, 200);
}
