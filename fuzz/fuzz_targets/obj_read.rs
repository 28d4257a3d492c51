//! OBJ text: reading never panics; a mesh that reads has finite vertices and in-range indices,
//! and its mass properties are a value or an error, never a panic.
#![no_main]

use libfuzzer_sys::fuzz_target;

#[path = "../../crates/tumble-io/tests/fuzz_support/mod.rs"]
mod fuzz_support;

fuzz_target!(|data: &[u8]| {
    if let Ok(text) = std::str::from_utf8(data) {
        fuzz_support::check_obj(text);
    }
});
