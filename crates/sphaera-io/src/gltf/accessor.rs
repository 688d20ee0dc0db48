//! Bounds-checked reading of glTF accessors: vertex positions and vertex indices.
//!
//! Every offset, length and stride comes from the file, so each is checked (with overflow
//! checks) before a byte is read; a bad one is a [`ParseReason`], never a panic. Handled:
//! interleaved views (`byteStride`), accessors without a buffer view (all zeros), sparse
//! accessors (over a buffer view or over zeros), and positions stored as 8- or 16-bit
//! integers, normalized or not (`KHR_mesh_quantization`), decoded with the glTF rules
//! (`max(c / 127, -1)` for a normalized signed byte, `c / 255` for an unsigned one, and so
//! on for 16 bits).
//!
//! Memory is reserved only for elements the data were checked to hold; an accessor
//! without a buffer view, which holds zeros, may have at most [`MAX_ZEROS`] elements.

use ::gltf::json::{
    self,
    accessor::{ComponentType, GenericComponentType, IndexComponentType, Type},
    validation::Checked,
};
use glam::DVec3;

use super::super::ParseReason;
use super::super::builder::finite_point;
use super::buffers::Buffers;

/// Bytes in one component.
fn component_size(component: ComponentType) -> usize {
    match component {
        ComponentType::I8 | ComponentType::U8 => 1,
        ComponentType::I16 | ComponentType::U16 => 2,
        ComponentType::U32 | ComponentType::F32 => 4,
    }
}

/// The glTF spelling of an element type.
fn type_name(ty: Type) -> &'static str {
    match ty {
        Type::Scalar => "SCALAR",
        Type::Vec2 => "VEC2",
        Type::Vec3 => "VEC3",
        Type::Vec4 => "VEC4",
        Type::Mat2 => "MAT2",
        Type::Mat3 => "MAT3",
        Type::Mat4 => "MAT4",
    }
}

/// A short name of a component type.
fn component_name(component: ComponentType) -> &'static str {
    match component {
        ComponentType::I8 => "i8",
        ComponentType::U8 => "u8",
        ComponentType::I16 => "i16",
        ComponentType::U16 => "u16",
        ComponentType::U32 => "u32",
        ComponentType::F32 => "f32",
    }
}

/// One component as a float, with the glTF normalization rules when `normalized`.
fn decode_float(component: ComponentType, normalized: bool, bytes: &[u8]) -> Option<f64> {
    Some(match component {
        ComponentType::F32 => f64::from(f32::from_le_bytes(bytes.try_into().ok()?)),
        ComponentType::I8 => {
            let v = f64::from(i8::from_le_bytes(bytes.try_into().ok()?));
            if normalized { (v / 127.0).max(-1.0) } else { v }
        }
        ComponentType::U8 => {
            let v = f64::from(u8::from_le_bytes(bytes.try_into().ok()?));
            if normalized { v / 255.0 } else { v }
        }
        ComponentType::I16 => {
            let v = f64::from(i16::from_le_bytes(bytes.try_into().ok()?));
            if normalized {
                (v / 32767.0).max(-1.0)
            } else {
                v
            }
        }
        ComponentType::U16 => {
            let v = f64::from(u16::from_le_bytes(bytes.try_into().ok()?));
            if normalized { v / 65535.0 } else { v }
        }
        ComponentType::U32 => {
            let v = f64::from(u32::from_le_bytes(bytes.try_into().ok()?));
            if normalized { v / 4_294_967_295.0 } else { v }
        }
    })
}

/// One unsigned integer component (an index).
fn decode_index(component: ComponentType, bytes: &[u8]) -> Option<u32> {
    match component {
        ComponentType::U8 => Some(u32::from(u8::from_le_bytes(bytes.try_into().ok()?))),
        ComponentType::U16 => Some(u32::from(u16::from_le_bytes(bytes.try_into().ok()?))),
        ComponentType::U32 => Some(u32::from_le_bytes(bytes.try_into().ok()?)),
        _ => None,
    }
}

/// The accessor `index`, its component type and element type.
fn accessor(
    root: &json::Root,
    index: usize,
) -> Result<(&json::Accessor, ComponentType, Type), ParseReason> {
    let accessor = root
        .accessors
        .get(index)
        .ok_or(ParseReason::DanglingReference {
            kind: "accessor",
            index,
            available: root.accessors.len(),
        })?;
    let Checked::Valid(GenericComponentType(component)) = accessor.component_type else {
        return Err(ParseReason::InvalidValue {
            what: "accessor component type",
        });
    };
    let Checked::Valid(ty) = accessor.type_ else {
        return Err(ParseReason::InvalidValue {
            what: "accessor type",
        });
    };
    Ok((accessor, component, ty))
}

/// The vertex positions of accessor `index`: `VEC3` of `f32`, or of 8/16-bit integers
/// (normalized or not). Refuses NaN and infinite coordinates.
pub(super) fn read_positions(
    root: &json::Root,
    buffers: &Buffers<'_>,
    index: usize,
) -> Result<Vec<DVec3>, ParseReason> {
    let (accessor, component, ty) = accessor(root, index)?;
    if ty != Type::Vec3 || component == ComponentType::U32 {
        return Err(ParseReason::UnexpectedAccessorType {
            accessor: index,
            expected: "VEC3 of f32, or of (normalized) 8- or 16-bit integers",
            found: format!("{} of {}", type_name(ty), component_name(component)),
        });
    }
    let normalized = accessor.normalized;
    let values = read_values(root, buffers, index, accessor, 3, component, 0.0, |bytes| {
        decode_float(component, normalized, bytes)
    })?;
    values
        .chunks_exact(3)
        .enumerate()
        .map(|(vertex, xyz)| finite_point([xyz[0], xyz[1], xyz[2]], vertex))
        .collect()
}

/// The vertex indices of accessor `index`: `SCALAR` of `u8`, `u16` or `u32`.
pub(super) fn read_indices(
    root: &json::Root,
    buffers: &Buffers<'_>,
    index: usize,
) -> Result<Vec<u32>, ParseReason> {
    let (accessor, component, ty) = accessor(root, index)?;
    let unsigned = matches!(
        component,
        ComponentType::U8 | ComponentType::U16 | ComponentType::U32
    );
    if ty != Type::Scalar || !unsigned {
        return Err(ParseReason::UnexpectedAccessorType {
            accessor: index,
            expected: "SCALAR of u8, u16 or u32",
            found: format!("{} of {}", type_name(ty), component_name(component)),
        });
    }
    read_values(root, buffers, index, accessor, 1, component, 0, |bytes| {
        decode_index(component, bytes)
    })
}

/// The most elements of an accessor without a buffer view (all zeros but for its sparse
/// values): 2²⁴, so that a few bytes of JSON cannot ask for gigabytes of zeros.
pub(super) const MAX_ZEROS: usize = 1 << 24;

/// Reserves room for `len` values, or the error for a count too large to hold.
fn reserve<T>(out: &mut Vec<T>, len: usize) -> Result<(), ParseReason> {
    out.try_reserve_exact(len)
        .map_err(|_| ParseReason::InvalidCount {
            what: "accessor count",
            value: len as f64,
        })
}

/// The element count of an accessor, at most `u32::MAX`.
fn element_count(accessor: &json::Accessor) -> Result<usize, ParseReason> {
    usize::try_from(accessor.count.0)
        .ok()
        .filter(|&count| count <= u32::MAX as usize)
        .ok_or(ParseReason::InvalidCount {
            what: "accessor count",
            value: accessor.count.0 as f64,
        })
}

/// The `components × count` values of an accessor, decoded by `decode` (one component's
/// bytes in, its value out), with its sparse substitution applied.
#[allow(clippy::too_many_arguments)]
fn read_values<T: Copy>(
    root: &json::Root,
    buffers: &Buffers<'_>,
    index: usize,
    accessor: &json::Accessor,
    components: usize,
    component: ComponentType,
    zero: T,
    decode: impl Fn(&[u8]) -> Option<T>,
) -> Result<Vec<T>, ParseReason> {
    let size = component_size(component);
    let element_size = components * size;
    let count = element_count(accessor)?;
    let mut out: Vec<T> = Vec::new();
    match accessor.buffer_view {
        Some(view) => {
            let view = view.value();
            let span = Span {
                accessor: index,
                part: "elements",
                view,
                offset: accessor.byte_offset.map_or(0, |o| o.0),
                count,
                element_size,
            };
            let (data, stride) = view_data(root, buffers, view, element_size, false)?;
            // Checked against the data first, so the reservation is bounded by the file.
            let elements = span.elements(data, stride)?;
            reserve(&mut out, count * components)?;
            for element in elements {
                let element = element?;
                for c in 0..components {
                    let value = element
                        .get(c * size..(c + 1) * size)
                        .and_then(&decode)
                        .ok_or_else(|| span.out_of_bounds(data, stride))?;
                    out.push(value);
                }
            }
        }
        None => {
            if count > MAX_ZEROS {
                return Err(ParseReason::InvalidCount {
                    what: "element count of an accessor without a buffer view",
                    value: count as f64,
                });
            }
            reserve(&mut out, count * components)?;
            out.resize(count * components, zero);
        }
    }
    if let Some(sparse) = &accessor.sparse {
        let sparse_count = usize::try_from(sparse.count.0).unwrap_or(usize::MAX);
        let Checked::Valid(IndexComponentType(index_component)) = sparse.indices.component_type
        else {
            return Err(ParseReason::InvalidValue {
                what: "sparse index component type",
            });
        };
        let index_size = component_size(index_component);
        let indices_view = sparse.indices.buffer_view.value();
        let indices = Span {
            accessor: index,
            part: "sparse indices",
            view: indices_view,
            offset: sparse.indices.byte_offset.0,
            count: sparse_count,
            element_size: index_size,
        };
        let values_view = sparse.values.buffer_view.value();
        let values = Span {
            accessor: index,
            part: "sparse values",
            view: values_view,
            offset: sparse.values.byte_offset.0,
            count: sparse_count,
            element_size,
        };
        let (index_data, index_stride) = view_data(root, buffers, indices_view, index_size, true)?;
        let (value_data, value_stride) = view_data(root, buffers, values_view, element_size, true)?;
        let targets = indices.elements(index_data, index_stride)?;
        let replacements = values.elements(value_data, value_stride)?;
        for (target, replacement) in targets.zip(replacements) {
            let (target, replacement) = (target?, replacement?);
            let target = decode_index(index_component, target)
                .ok_or_else(|| indices.out_of_bounds(index_data, index_stride))?;
            let out_of_range = || ParseReason::SparseIndexOutOfRange {
                accessor: index,
                index: u64::from(target),
                count,
            };
            let first = (target as usize)
                .checked_mul(components)
                .ok_or_else(out_of_range)?;
            let slots = out
                .get_mut(first..first + components)
                .ok_or_else(out_of_range)?;
            for (c, slot) in slots.iter_mut().enumerate() {
                *slot = replacement
                    .get(c * size..(c + 1) * size)
                    .and_then(&decode)
                    .ok_or_else(|| values.out_of_bounds(value_data, value_stride))?;
            }
        }
    }
    Ok(out)
}

/// The bytes of buffer view `view` and its stride (the element size when the view has
/// none, or when `tight`, as for sparse data, which the spec stores tightly packed).
fn view_data<'b>(
    root: &json::Root,
    buffers: &'b Buffers<'_>,
    view: usize,
    element_size: usize,
    tight: bool,
) -> Result<(&'b [u8], usize), ParseReason> {
    let json_view = root
        .buffer_views
        .get(view)
        .ok_or(ParseReason::DanglingReference {
            kind: "buffer view",
            index: view,
            available: root.buffer_views.len(),
        })?;
    let buffer = json_view.buffer.value();
    let dangling = ParseReason::DanglingReference {
        kind: "buffer",
        index: buffer,
        available: root.buffers.len(),
    };
    let declared = root
        .buffers
        .get(buffer)
        .ok_or(dangling.clone())?
        .byte_length
        .0;
    let data = buffers.get(buffer).ok_or(dangling)?;
    let offset = json_view.byte_offset.map_or(0, |o| o.0);
    let end = offset.checked_add(json_view.byte_length.0);
    let out_of_bounds = || ParseReason::BufferViewOutOfBounds {
        view,
        buffer,
        end: end.unwrap_or(u64::MAX),
        available: declared,
    };
    let slice = match end {
        Some(end) if end <= declared => usize::try_from(offset)
            .ok()
            .zip(usize::try_from(end).ok())
            .and_then(|(start, end)| data.get(start..end))
            .ok_or_else(out_of_bounds)?,
        _ => return Err(out_of_bounds()),
    };
    let stride = match json_view.byte_stride {
        Some(stride) if !tight => stride.0,
        _ => element_size,
    };
    if stride < element_size || stride == 0 {
        return Err(ParseReason::InvalidStride {
            view,
            stride,
            element_size,
        });
    }
    Ok((slice, stride))
}

/// Where the elements of one part of an accessor lie in their buffer view.
struct Span {
    accessor: usize,
    part: &'static str,
    view: usize,
    offset: u64,
    count: usize,
    element_size: usize,
}

impl Span {
    /// The end of the last element, in bytes from the view's start (`None` on overflow).
    fn end(&self, stride: usize) -> Option<u64> {
        if self.count == 0 {
            return Some(self.offset);
        }
        (self.count as u64 - 1)
            .checked_mul(stride as u64)?
            .checked_add(self.offset)?
            .checked_add(self.element_size as u64)
    }

    fn out_of_bounds(&self, data: &[u8], stride: usize) -> ParseReason {
        ParseReason::AccessorOutOfBounds {
            accessor: self.accessor,
            part: self.part,
            view: self.view,
            end: self.end(stride).unwrap_or(u64::MAX),
            available: data.len() as u64,
        }
    }

    /// The bytes of each element, after checking that they all lie in `data`.
    fn elements<'d>(
        &self,
        data: &'d [u8],
        stride: usize,
    ) -> Result<impl Iterator<Item = Result<&'d [u8], ParseReason>> + use<'d, '_>, ParseReason>
    {
        match self.end(stride) {
            Some(end) if end <= data.len() as u64 => {}
            _ => return Err(self.out_of_bounds(data, stride)),
        }
        // In bounds, so `offset` fits a usize.
        let offset = usize::try_from(self.offset).unwrap_or(usize::MAX);
        Ok((0..self.count).map(move |i| {
            let start = offset + i * stride;
            data.get(start..start + self.element_size)
                .ok_or_else(|| self.out_of_bounds(data, stride))
        }))
    }
}
