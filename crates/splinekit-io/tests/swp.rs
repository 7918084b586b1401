//! Integration tests of the SWP reader and writer (one test binary; modules in `tests/swp/`).

mod swp {
    pub mod common;
    mod errors;
    mod extensions;
    mod files;
    mod properties;
    mod validate;
}
