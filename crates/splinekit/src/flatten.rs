//! Tessellation of curves into polylines (SPEC §1.3). Work in progress.
