// The 3D view's shaders: the shaded surface with its wireframe overlay, and the normal lines.
//
// Colours are written gamma-encoded (sRGB) into an Rgba8Unorm texture, which is what egui's
// renderer expects of a native texture; lighting is computed in linear RGB.

struct Uniforms {
    // Clip from render space (world minus the mesh origin).
    view_proj: mat4x4<f32>,
    // xyz: the eye in render space.
    eye: vec4<f32>,
    // xyz: unit direction towards the key light.
    light: vec4<f32>,
    // Linear RGB colours.
    front: vec4<f32>,
    back: vec4<f32>,
    // rgb: wireframe colour; a: half the line width in pixels.
    wire: vec4<f32>,
    normal_line: vec4<f32>,
    // x: wireframe, y: smooth, z: back-face colour, w: vertex colours (1 = on; 2 = a UV
    // checker, the vertex colours' red and green being the UVs, their fractional parts).
    flags: vec4<f32>,
};

@group(0) @binding(0) var<uniform> u: Uniforms;

struct SurfaceIn {
    @location(0) position: vec3<f32>,
    @location(1) normal: vec3<f32>,
    @location(2) color: vec4<f32>,
};

struct SurfaceOut {
    @builtin(position) clip: vec4<f32>,
    @location(0) world: vec3<f32>,
    @location(1) normal: vec3<f32>,
    @location(2) color: vec4<f32>,
    @location(3) bary: vec3<f32>,
};

fn linear_from_srgb(c: vec3<f32>) -> vec3<f32> {
    let lo = c / 12.92;
    let hi = pow((c + 0.055) / 1.055, vec3<f32>(2.4));
    return select(hi, lo, c <= vec3<f32>(0.04045));
}

fn srgb_from_linear(c: vec3<f32>) -> vec3<f32> {
    let x = clamp(c, vec3<f32>(0.0), vec3<f32>(1.0));
    let lo = x * 12.92;
    let hi = 1.055 * pow(x, vec3<f32>(1.0 / 2.4)) - 0.055;
    return select(hi, lo, x <= vec3<f32>(0.0031308));
}

// Triangles are drawn unindexed, three vertices each, so the corner is the vertex index mod 3.
@vertex
fn vs_surface(in: SurfaceIn, @builtin(vertex_index) index: u32) -> SurfaceOut {
    var out: SurfaceOut;
    out.clip = u.view_proj * vec4<f32>(in.position, 1.0);
    out.world = in.position;
    out.normal = in.normal;
    out.color = in.color;
    let k = index % 3u;
    out.bary = vec3<f32>(f32(k == 0u), f32(k == 1u), f32(k == 2u));
    return out;
}

@fragment
fn fs_surface(in: SurfaceOut, @builtin(front_facing) front_facing: bool) -> @location(0) vec4<f32> {
    // Derivatives first, in uniform control flow.
    let ng_raw = cross(dpdx(in.world), dpdy(in.world));
    let bary_width = fwidth(in.bary);

    let to_eye = normalize(u.eye.xyz - in.world);
    // The geometric normal, turned towards the eye: whichever side is seen is lit.
    var ng = to_eye;
    let ng_len = length(ng_raw);
    if ng_len > 0.0 {
        ng = ng_raw / ng_len;
    }
    if dot(ng, to_eye) < 0.0 {
        ng = -ng;
    }
    var n = ng;
    if u.flags.y > 0.5 {
        let len = length(in.normal);
        if len > 1e-20 {
            n = in.normal / len;
            // Vertex normals point out of the front; on the other side, or on a mesh whose
            // normals disagree with its winding, turn them to the seen side.
            if dot(n, ng) < 0.0 {
                n = -n;
            }
        }
    }

    var base = u.front.rgb;
    if u.flags.w > 1.5 {
        // 8 squares per unit of u and of v (the render crate's CHECKER_SQUARES and colours)
        let cell = floor(in.color.rg * 8.0);
        let odd = (i32(cell.x) + i32(cell.y)) % 2 != 0;
        base = select(linear_from_srgb(vec3<f32>(225.0) / 255.0), linear_from_srgb(vec3<f32>(70.0, 105.0, 165.0) / 255.0), odd);
    } else if u.flags.w > 0.5 {
        base = linear_from_srgb(in.color.rgb);
    }
    if !front_facing && u.flags.z > 0.5 {
        base = u.back.rgb;
    }

    let l = u.light.xyz;
    let diffuse = max(dot(n, l), 0.0);
    let h = normalize(l + to_eye);
    let specular = 0.2 * pow(max(dot(n, h), 0.0), 40.0);
    // Some light from the eye too, so faces turned from the key light keep their shape.
    let fill = 0.25 * max(dot(n, to_eye), 0.0);
    var c = base * (0.12 + 0.7 * diffuse + fill) + vec3<f32>(specular);

    if u.flags.x > 0.5 {
        // Distance to the nearest edge in pixels; both triangles of an edge draw their half.
        let px = in.bary / max(bary_width, vec3<f32>(1e-8));
        let d = min(px.x, min(px.y, px.z));
        let w = u.wire.a;
        let edge = 1.0 - smoothstep(w - 0.5, w + 0.5, d);
        c = mix(c, u.wire.rgb, edge);
    }
    return vec4<f32>(srgb_from_linear(c), 1.0);
}

@vertex
fn vs_line(@location(0) position: vec3<f32>) -> @builtin(position) vec4<f32> {
    return u.view_proj * vec4<f32>(position, 1.0);
}

@fragment
fn fs_line() -> @location(0) vec4<f32> {
    return vec4<f32>(srgb_from_linear(u.normal_line.rgb), 1.0);
}
