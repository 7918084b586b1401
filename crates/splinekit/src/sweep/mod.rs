//! Swept surfaces (SPEC §2). Work in progress.
