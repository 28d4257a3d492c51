//! STL bytes (binary or ASCII): as `obj_read`.
#![no_main]

use libfuzzer_sys::fuzz_target;

#[path = "../../crates/tumble-io/tests/fuzz_support/mod.rs"]
mod fuzz_support;

fuzz_target!(|data: &[u8]| fuzz_support::check_stl(data));
