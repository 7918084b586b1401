//! Measures what reading `.glb` files with the `gltf` crate would give instead of
//! splinekit-io's reader (the module doc of `splinekit_io::mesh::glb_read` cites the result):
//! on the fuzzer's generated and mutated `.glb` cases, how often each reader accepts or
//! refuses a file, how often `gltf` panics, and whether an error says where the problem is.
//!
//! `cargo run --release -p splinekit-fuzz --example gltf_probe -- [CASES] [SEED]`

use std::panic::{AssertUnwindSafe, catch_unwind};

use splinekit_fuzz::Format;
use splinekit_fuzz::corpus::Corpus;
use splinekit_fuzz::harness::make_case;

/// Reads every triangle primitive's positions and indices with `gltf`'s own reader, as a
/// reader built on the crate would; the count of triangles read.
fn read_with_gltf(bytes: &[u8]) -> Result<usize, String> {
    let gltf = gltf::Gltf::from_slice(bytes).map_err(|e| e.to_string())?;
    let blob = gltf.blob.as_deref();
    let mut triangles = 0;
    for mesh in gltf.meshes() {
        for primitive in mesh.primitives() {
            let reader = primitive.reader(|buffer| match buffer.source() {
                gltf::buffer::Source::Bin => blob,
                gltf::buffer::Source::Uri(_) => None,
            });
            let positions: Vec<[f32; 3]> = reader.read_positions().ok_or("no positions (or not readable)")?.collect();
            triangles += match reader.read_indices() {
                Some(indices) => indices.into_u32().count() / 3,
                None => positions.len() / 3,
            };
        }
    }
    Ok(triangles)
}

fn main() {
    let mut args = std::env::args().skip(1);
    let cases: u64 = args.next().and_then(|a| a.parse().ok()).unwrap_or(20_000);
    let seed: u64 = args.next().and_then(|a| a.parse().ok()).unwrap_or(7);
    std::panic::set_hook(Box::new(|_| {}));
    let corpus = Corpus::load(&[]);
    let (mut ours_ok, mut ours_err, mut gltf_ok, mut gltf_err, mut gltf_panic) = (0, 0, 0, 0, 0);
    let (mut ok_but_gltf_refuses, mut refused_but_gltf_reads) = (0, 0);
    let mut samples = Vec::new();
    let mut read_samples = Vec::new();
    let mut panics = Vec::new();
    for index in 0..cases {
        let case = make_case(seed, index, Some(Format::Glb), &corpus);
        let ours = splinekit_io::mesh::read_glb(case.input.as_slice(), "case.glb");
        match &ours {
            Ok(_) => ours_ok += 1,
            Err(_) => ours_err += 1,
        }
        match catch_unwind(AssertUnwindSafe(|| read_with_gltf(&case.input))) {
            Ok(Ok(_)) => {
                gltf_ok += 1;
                if let Err(e) = &ours {
                    refused_but_gltf_reads += 1;
                    if read_samples.len() < 8 {
                        read_samples.push(format!("  {e}"));
                    }
                }
            }
            Ok(Err(message)) => {
                gltf_err += 1;
                if ours.is_ok() {
                    ok_but_gltf_refuses += 1;
                }
                if let Err(e) = &ours
                    && samples.len() < 6
                {
                    samples.push(format!("  ours: {e}\n  gltf: {message}"));
                }
            }
            Err(payload) => {
                gltf_panic += 1;
                let text = payload
                    .downcast_ref::<String>()
                    .cloned()
                    .or_else(|| payload.downcast_ref::<&str>().map(|s| (*s).to_owned()));
                if panics.len() < 4 {
                    panics.push(format!("  case {index}: {}", text.unwrap_or_default()));
                }
            }
        }
    }
    println!("{cases} glb cases (seed {seed})");
    println!("splinekit-io: {ours_ok} read, {ours_err} refused with an error");
    println!("gltf 1.4:     {gltf_ok} read, {gltf_err} refused with an error, {gltf_panic} panicked");
    println!("read by splinekit-io but refused by gltf: {ok_but_gltf_refuses}");
    println!("refused by splinekit-io but read by gltf: {refused_but_gltf_reads}");
    println!("errors side by side:\n{}", samples.join("\n"));
    println!("refused by splinekit-io, read by gltf:\n{}", read_samples.join("\n"));
    println!("gltf panics:\n{}", panics.join("\n"));
}
