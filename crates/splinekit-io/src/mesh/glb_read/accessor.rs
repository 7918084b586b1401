//! Accessors: the elements of an attribute or index list, checked against their buffer view,
//! and what each attribute accepts.

use glam::DVec3;
use gltf_json as json;
use json::accessor::{ComponentType, Type};
use json::validation::Checked::Valid;

use super::super::MeshIoError;
use super::container::Buffer;
use super::{below, invalid};

/// The elements of an accessor, checked to lie within their buffer.
pub(super) struct Elements<'a> {
    /// From the first byte of the first element to the end of the buffer view.
    pub(super) data: &'a [u8],
    pub(super) stride: usize,
    pub(super) count: usize,
    pub(super) component: ComponentType,
    pub(super) normalized: bool,
}

impl Elements<'_> {
    /// Component `k` of element `i` as a number (normalized integers mapped to `[0, 1]` or
    /// `[-1, 1]`).
    pub(super) fn get(&self, i: usize, k: usize) -> f64 {
        let size = self.component.size();
        let at = i * self.stride + k * size;
        let Some(b) = self.data.get(at..at + size) else { return 0.0 };
        let n = self.normalized;
        match self.component {
            ComponentType::F32 => f64::from(f32::from_le_bytes([b[0], b[1], b[2], b[3]])),
            ComponentType::U8 => f64::from(b[0]) / if n { 255.0 } else { 1.0 },
            ComponentType::I8 => {
                let v = f64::from(b[0] as i8);
                if n { (v / 127.0).max(-1.0) } else { v }
            }
            ComponentType::U16 => f64::from(u16::from_le_bytes([b[0], b[1]])) / if n { 65535.0 } else { 1.0 },
            ComponentType::I16 => {
                let v = f64::from(i16::from_le_bytes([b[0], b[1]]));
                if n { (v / 32767.0).max(-1.0) } else { v }
            }
            ComponentType::U32 => {
                f64::from(u32::from_le_bytes([b[0], b[1], b[2], b[3]])) / if n { f64::from(u32::MAX) } else { 1.0 }
            }
        }
    }

    /// Element `i` of an unsigned integer accessor.
    pub(super) fn index(&self, i: usize) -> u32 {
        let size = self.component.size();
        let at = i * self.stride;
        let Some(b) = self.data.get(at..at + size) else { return u32::MAX };
        match self.component {
            ComponentType::U8 | ComponentType::I8 => u32::from(b[0]),
            ComponentType::U16 | ComponentType::I16 => u32::from(u16::from_le_bytes([b[0], b[1]])),
            ComponentType::U32 | ComponentType::F32 => u32::from_le_bytes([b[0], b[1], b[2], b[3]]),
        }
    }

    pub(super) fn vec3(&self, i: usize) -> DVec3 {
        DVec3::new(self.get(i, 0), self.get(i, 1), self.get(i, 2))
    }
}

/// The name of a component type, like `f32`.
pub(super) fn component_name(c: ComponentType) -> &'static str {
    match c {
        ComponentType::I8 => "i8",
        ComponentType::U8 => "u8",
        ComponentType::I16 => "i16",
        ComponentType::U16 => "u16",
        ComponentType::U32 => "u32",
        ComponentType::F32 => "f32",
    }
}

/// The name of an accessor type, like `VEC3`, and its number of components.
pub(super) fn type_info(t: Type) -> (&'static str, usize) {
    match t {
        Type::Scalar => ("SCALAR", 1),
        Type::Vec2 => ("VEC2", 2),
        Type::Vec3 => ("VEC3", 3),
        Type::Vec4 => ("VEC4", 4),
        Type::Mat2 => ("MAT2", 4),
        Type::Mat3 => ("MAT3", 9),
        Type::Mat4 => ("MAT4", 16),
    }
}

/// What an attribute accepts: a description for errors and the test.
pub(super) struct Accepts {
    pub(super) expected: &'static str,
    pub(super) ok: fn(ComponentType, Type, bool) -> bool,
}

pub(super) const POSITIONS: Accepts = Accepts {
    expected: "f32 VEC3 (quantized positions are not supported)",
    ok: |c, t, _| c == ComponentType::F32 && t == Type::Vec3,
};
pub(super) const NORMALS: Accepts = Accepts {
    expected: "f32, or normalized i8 or i16, VEC3",
    ok: |c, t, n| {
        t == Type::Vec3 && (c == ComponentType::F32 || n && matches!(c, ComponentType::I8 | ComponentType::I16))
    },
};
pub(super) const TEXCOORDS: Accepts = Accepts {
    expected: "f32, or normalized u8, u16, i8 or i16, VEC2",
    ok: |c, t, n| t == Type::Vec2 && (c == ComponentType::F32 || n && c != ComponentType::U32),
};
pub(super) const COLORS: Accepts = Accepts {
    expected: "f32, or normalized u8 or u16, VEC3 or VEC4",
    ok: |c, t, n| {
        matches!(t, Type::Vec3 | Type::Vec4)
            && (c == ComponentType::F32 || n && matches!(c, ComponentType::U8 | ComponentType::U16))
    },
};
pub(super) const INDICES: Accepts = Accepts {
    expected: "u8, u16 or u32 SCALAR",
    ok: |c, t, n| t == Type::Scalar && !n && matches!(c, ComponentType::U8 | ComponentType::U16 | ComponentType::U32),
};

/// A parsed document with its buffers.
pub(super) struct Doc<'a> {
    pub(super) origin: &'a str,
    pub(super) root: &'a json::Root,
    pub(super) buffers: Vec<Buffer<'a>>,
}

impl Doc<'_> {
    pub(super) fn error(&self, at: impl Into<String>, message: impl Into<String>) -> MeshIoError {
        invalid(self.origin, at, message)
    }

    /// Accessor `index`, referenced at `at`, checked against `accepts` and its buffer view.
    pub(super) fn accessor(&self, index: usize, at: &str, accepts: &Accepts) -> Result<Elements<'_>, MeshIoError> {
        let root = self.root;
        let Some(accessor) = root.accessors.get(index) else {
            return Err(self.error(at, format!("found accessor {index}, {}", below(root.accessors.len(), "accessors"))));
        };
        let here = format!("{at} (accessors[{index}])");
        if accessor.sparse.is_some() {
            return Err(
                self.error(here, "found a sparse accessor, expected a plain one (sparse accessors are not supported)")
            );
        }
        let Valid(json::accessor::GenericComponentType(component)) = accessor.component_type else {
            return Err(
                self.error(here, "found an invalid componentType, expected 5120, 5121, 5122, 5123, 5125 or 5126")
            );
        };
        let Valid(type_) = accessor.type_ else {
            return Err(self.error(here, "found an invalid type, expected SCALAR, VEC2, VEC3, VEC4 or a matrix"));
        };
        let normalized = accessor.normalized;
        let (type_name, components) = type_info(type_);
        if !(accepts.ok)(component, type_, normalized) {
            let norm = if normalized { "normalized " } else { "" };
            return Err(self.error(
                here,
                format!("found {norm}{} {type_name}, expected {}", component_name(component), accepts.expected),
            ));
        }
        let Some(v) = accessor.buffer_view.map(|v| v.value()) else {
            return Err(self.error(here, "found no bufferView, expected one (accessors of zeros are not supported)"));
        };
        let Some(view) = root.buffer_views.get(v) else {
            return Err(self.error(
                format!("{here}.bufferView"),
                format!("found buffer view {v}, {}", below(root.buffer_views.len(), "buffer views")),
            ));
        };
        let b = view.buffer.value();
        let buffer = match self.buffers.get(b) {
            Some(Ok(buffer)) => buffer,
            Some(Err((at, message))) => return Err(self.error(at.clone(), message.clone())),
            None => {
                return Err(self.error(
                    format!("bufferViews[{v}].buffer"),
                    format!("found buffer {b}, {}", below(root.buffers.len(), "buffers")),
                ));
            }
        };
        let view_start = view.byte_offset.map_or(0, |o| o.0);
        let view_length = view.byte_length.0;
        let view_end = view_start.saturating_add(view_length);
        if view_end > buffer.len() as u64 {
            return Err(self.error(
                format!("bufferViews[{v}]"),
                format!(
                    "found bytes {view_start}..{view_end} of buffers[{b}], which has {} bytes, expected a view within its buffer",
                    buffer.len()
                ),
            ));
        }
        let element = (component.size() * components) as u64;
        let stride = view.byte_stride.map_or(element, |s| s.0 as u64);
        if stride < element {
            return Err(self.error(
                format!("bufferViews[{v}].byteStride"),
                format!("found {stride}, expected at least {element} (the size of an element of accessors[{index}])"),
            ));
        }
        let offset = accessor.byte_offset.map_or(0, |o| o.0);
        let count = accessor.count.0;
        if count > 0 {
            let end = (count - 1)
                .checked_mul(stride)
                .and_then(|e| e.checked_add(offset))
                .and_then(|e| e.checked_add(element));
            if end.is_none_or(|end| end > view_length) {
                let end = end.map_or_else(|| String::from("beyond 2⁶⁴"), |e| e.to_string());
                return Err(self.error(
                    here,
                    format!(
                        "found {count} elements of {element} bytes every {stride} bytes from byte {offset} (up to byte {end}), expected them within bufferViews[{v}] of {view_length} bytes"
                    ),
                ));
            }
        }
        // In bounds: view_end <= buffer.len(), and offset <= view_length when count > 0.
        let start = (view_start + offset.min(view_length)) as usize;
        let data = &buffer[start..view_end as usize];
        Ok(Elements { data, stride: stride as usize, count: count as usize, component, normalized })
    }
}
