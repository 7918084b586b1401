//! Frames along curves (SPEC §1.5). Work in progress.
