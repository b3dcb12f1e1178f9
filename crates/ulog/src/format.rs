//! Message formats (`F` messages): ULog's primitive types, a format's
//! fields, the byte size of a topic's samples and its fields flattened into
//! the names pyulog gives them (`gyro_rad[0]`, `esc[5].esc_rpm`).

use std::collections::HashMap;

use crate::bytes::at;
use crate::error::shorten;

/// Nesting deeper than this is refused (PX4's topics nest at most 3 levels);
/// it bounds the recursion on a hostile file.
pub(crate) const MAX_NESTING: usize = 32;

/// The largest payload of a data message after its 2-byte message id.
pub(crate) const MAX_SAMPLE_BYTES: usize = u16::MAX as usize - 2;

/// A primitive ULog type.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum FieldType {
    Int8,
    UInt8,
    Int16,
    UInt16,
    Int32,
    UInt32,
    Int64,
    UInt64,
    Float,
    Double,
    Bool,
    Char,
}

impl FieldType {
    const ALL: [FieldType; 12] = [
        Self::Int8,
        Self::UInt8,
        Self::Int16,
        Self::UInt16,
        Self::Int32,
        Self::UInt32,
        Self::Int64,
        Self::UInt64,
        Self::Float,
        Self::Double,
        Self::Bool,
        Self::Char,
    ];

    /// The type as a format message spells it.
    pub fn name(self) -> &'static str {
        match self {
            Self::Int8 => "int8_t",
            Self::UInt8 => "uint8_t",
            Self::Int16 => "int16_t",
            Self::UInt16 => "uint16_t",
            Self::Int32 => "int32_t",
            Self::UInt32 => "uint32_t",
            Self::Int64 => "int64_t",
            Self::UInt64 => "uint64_t",
            Self::Float => "float",
            Self::Double => "double",
            Self::Bool => "bool",
            Self::Char => "char",
        }
    }

    /// The type of a format message's spelling, if primitive.
    pub fn parse(name: &str) -> Option<Self> {
        Self::ALL.into_iter().find(|t| t.name() == name)
    }

    /// Bytes of one value.
    pub fn size(self) -> usize {
        match self {
            Self::Int8 | Self::UInt8 | Self::Bool | Self::Char => 1,
            Self::Int16 | Self::UInt16 => 2,
            Self::Int32 | Self::UInt32 | Self::Float => 4,
            Self::Int64 | Self::UInt64 | Self::Double => 8,
        }
    }

    /// An integer type (a time stamp or interval in µs must be one).
    pub fn is_integer(self) -> bool {
        !matches!(self, Self::Float | Self::Double | Self::Bool | Self::Char)
    }

    /// The value at `offset` as f64 (bool 0/1, char its byte), or `None`
    /// past the end of `bytes`.
    pub(crate) fn decode(self, bytes: &[u8], offset: usize) -> Option<f64> {
        Some(match self {
            Self::Float => f32::from_le_bytes(at(bytes, offset)?) as f64,
            Self::Double => f64::from_le_bytes(at(bytes, offset)?),
            Self::Bool | Self::Char => at::<1>(bytes, offset)?[0] as f64,
            _ => self.decode_integer(bytes, offset)? as f64,
        })
    }

    /// The integer at `offset`, or `None` for a non-integer type or past
    /// the end of `bytes`.
    pub(crate) fn decode_integer(self, bytes: &[u8], offset: usize) -> Option<i128> {
        Some(match self {
            Self::Int8 => i8::from_le_bytes(at(bytes, offset)?) as i128,
            Self::UInt8 => u8::from_le_bytes(at(bytes, offset)?) as i128,
            Self::Int16 => i16::from_le_bytes(at(bytes, offset)?) as i128,
            Self::UInt16 => u16::from_le_bytes(at(bytes, offset)?) as i128,
            Self::Int32 => i32::from_le_bytes(at(bytes, offset)?) as i128,
            Self::UInt32 => u32::from_le_bytes(at(bytes, offset)?) as i128,
            Self::Int64 => i64::from_le_bytes(at(bytes, offset)?) as i128,
            Self::UInt64 => u64::from_le_bytes(at(bytes, offset)?) as i128,
            Self::Float | Self::Double | Self::Bool | Self::Char => return None,
        })
    }
}

/// The type of a format's field: primitive, or another format by name.
#[derive(Debug, Clone, PartialEq, Eq)]
pub(crate) enum TypeRef {
    Primitive(FieldType),
    Nested(String),
}

/// One field of a format as written: `type[count] name`.
#[derive(Debug, Clone, PartialEq, Eq)]
pub(crate) struct RawField {
    pub ty: TypeRef,
    /// `Some(n)` for an array `type[n]`.
    pub count: Option<usize>,
    pub name: String,
}

impl RawField {
    fn is_padding(&self) -> bool {
        self.name.starts_with("_padding")
    }

    fn copies(&self) -> usize {
        self.count.unwrap_or(1)
    }
}

/// A format message: a name and its fields.
#[derive(Debug, Clone, PartialEq, Eq)]
pub(crate) struct FormatDef {
    pub name: String,
    pub fields: Vec<RawField>,
}

/// Parses the payload of an `F` message, `name:type name;type[n] name;…`.
pub(crate) fn parse_format(payload: &[u8]) -> Result<FormatDef, String> {
    let text = std::str::from_utf8(payload).map_err(|_| "not UTF-8 text".to_string())?;
    let (name, fields) = text
        .split_once(':')
        .ok_or_else(|| format!("'{}' has no ':' after the name", shorten(text)))?;
    if name.is_empty() || name.chars().any(char::is_control) {
        return Err(format!(
            "'{}' has an empty name or one with control characters",
            shorten(text)
        ));
    }
    let fields = fields
        .split(';')
        .filter(|f| !f.trim().is_empty())
        .map(|f| parse_field(f).map_err(|e| format!("{name}: field '{}': {e}", shorten(f))))
        .collect::<Result<Vec<RawField>, _>>()?;
    let mut seen = std::collections::HashSet::new();
    if let Some(f) = fields.iter().find(|f| !seen.insert(f.name.as_str())) {
        return Err(format!("{name}: field '{}' appears twice", f.name));
    }
    Ok(FormatDef {
        name: name.to_string(),
        fields,
    })
}

fn parse_field(text: &str) -> Result<RawField, String> {
    let mut parts = text.split_whitespace();
    let (Some(ty), Some(name), None) = (parts.next(), parts.next(), parts.next()) else {
        return Err("not 'type name'".into());
    };
    let (base, count) = match ty.split_once('[') {
        None => (ty, None),
        Some((base, rest)) => {
            let n = rest
                .strip_suffix(']')
                .and_then(|n| n.parse::<usize>().ok())
                .filter(|&n| n > 0 && n <= MAX_SAMPLE_BYTES)
                .ok_or("the array size is not an integer from 1 to 65533")?;
            (base, Some(n))
        }
    };
    if base.is_empty() || text.chars().any(char::is_control) {
        return Err("an empty type, or control characters".into());
    }
    if !name.chars().all(|c| c.is_ascii_alphanumeric() || c == '_') {
        return Err("the name is not an identifier (letters, digits and _)".into());
    }
    let ty = FieldType::parse(base)
        .map_or_else(|| TypeRef::Nested(base.to_string()), TypeRef::Primitive);
    Ok(RawField {
        ty,
        count,
        name: name.to_string(),
    })
}

/// The byte sizes of a topic's samples: with the trailing `_padding` fields
/// the format declares, and without them (PX4's logger drops them, so a
/// data message may be either).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) struct Layout {
    pub size: usize,
    pub min_size: usize,
}

/// One primitive value of a flattened format.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct FlatField {
    /// The name pyulog gives it: `x`, `gyro_rad[0]`, `esc[5].esc_rpm`.
    pub name: String,
    pub ty: FieldType,
    /// Byte offset in a sample (after the message id).
    pub offset: usize,
}

/// The formats of a log, with their sizes computed once each.
#[derive(Debug, Clone, Default)]
pub(crate) struct Formats {
    defs: HashMap<String, FormatDef>,
    sizes: HashMap<String, usize>,
}

impl Formats {
    /// Adds (or replaces, as pyulog does) a format.
    pub fn insert(&mut self, def: FormatDef) {
        self.sizes.clear();
        self.defs.insert(def.name.clone(), def);
    }

    /// The layout of a topic's samples.
    pub fn layout(&mut self, name: &str) -> Result<Layout, String> {
        let size = self.size(name, &mut Vec::new())?;
        let trailing: Vec<RawField> = self.defs[name]
            .fields
            .iter()
            .rev()
            .take_while(|f| f.is_padding())
            .cloned()
            .collect();
        let mut min_size = size;
        for f in &trailing {
            min_size = min_size.saturating_sub(self.field_size(f, &mut vec![name.to_string()])?);
        }
        if min_size == 0 {
            return Err("its format has no fields but padding".into());
        }
        if size > MAX_SAMPLE_BYTES {
            return Err(format!(
                "its format is {size} bytes, more than a ULog data message holds ({MAX_SAMPLE_BYTES})"
            ));
        }
        Ok(Layout { size, min_size })
    }

    fn size(&mut self, name: &str, stack: &mut Vec<String>) -> Result<usize, String> {
        if let Some(&s) = self.sizes.get(name) {
            return Ok(s);
        }
        if stack.iter().any(|s| s == name) {
            return Err(format!("format '{}' contains itself", shorten(name)));
        }
        if stack.len() >= MAX_NESTING {
            return Err(format!("formats nest deeper than {MAX_NESTING} levels"));
        }
        let def = self
            .defs
            .get(name)
            .ok_or_else(|| format!("no format '{}' is defined", shorten(name)))?
            .clone();
        stack.push(name.to_string());
        let mut total = 0usize;
        for f in &def.fields {
            total = total.saturating_add(self.field_size(f, stack)?);
        }
        stack.pop();
        self.sizes.insert(name.to_string(), total);
        Ok(total)
    }

    fn field_size(&mut self, f: &RawField, stack: &mut Vec<String>) -> Result<usize, String> {
        let one = match &f.ty {
            TypeRef::Primitive(t) => t.size(),
            TypeRef::Nested(n) => match self.size(n, stack)? {
                0 => return Err(format!("format '{n}' (field '{}') has no fields", f.name)),
                s => s,
            },
        };
        Ok(one.saturating_mul(f.copies()))
    }

    /// The fields of a format whose [`Formats::layout`] succeeded, flattened
    /// (padding left out; nothing past the trailing padding), at most
    /// `limit` of them.
    pub fn flatten(&self, name: &str, limit: usize) -> Vec<FlatField> {
        let mut out = Vec::new();
        if let Some(def) = self.defs.get(name) {
            let keep = def.fields.len()
                - def
                    .fields
                    .iter()
                    .rev()
                    .take_while(|f| f.is_padding())
                    .count();
            self.push_fields(&def.fields[..keep], "", 0, 0, &mut (&mut out, limit));
        }
        out
    }

    /// A field of a format (whose layout succeeded) by its flattened name
    /// (`x`, `gyro_rad[0]`, `esc[5].esc_rpm`), found without flattening
    /// the rest.
    pub fn field(&self, format: &str, path: &str) -> Option<FlatField> {
        let mut def = self.defs.get(format)?;
        let mut offset = 0;
        let mut rest = path;
        loop {
            let (part, tail) = match rest.split_once('.') {
                Some((part, tail)) => (part, Some(tail)),
                None => (rest, None),
            };
            let (name, index) = match part.strip_suffix(']').and_then(|p| p.split_once('[')) {
                Some((name, k)) => (name, Some(k.parse::<usize>().ok()?)),
                None => (part, None),
            };
            let mut at = 0;
            let mut found = None;
            for f in &def.fields {
                let one = match &f.ty {
                    TypeRef::Primitive(t) => t.size(),
                    TypeRef::Nested(n) => *self.sizes.get(n)?,
                };
                if f.name == name && !f.is_padding() {
                    found = Some((f, one));
                    break;
                }
                at += one * f.copies();
            }
            let (f, one) = found?;
            offset += at;
            match (f.count, index) {
                (Some(n), Some(k)) if k < n => offset += k * one,
                (None, None) => {}
                _ => return None,
            }
            match (&f.ty, tail) {
                (TypeRef::Primitive(ty), None) => {
                    return Some(FlatField {
                        name: path.to_string(),
                        ty: *ty,
                        offset,
                    });
                }
                (TypeRef::Nested(n), Some(tail)) => {
                    def = self.defs.get(n)?;
                    rest = tail;
                }
                _ => return None,
            }
        }
    }

    /// The byte offset of a top-level `uint64_t timestamp` field, if the
    /// format (whose layout succeeded) has one.
    pub fn timestamp_offset(&self, name: &str) -> Option<usize> {
        let mut offset = 0;
        for f in &self.defs.get(name)?.fields {
            if f.name == "timestamp"
                && f.count.is_none()
                && f.ty == TypeRef::Primitive(FieldType::UInt64)
            {
                return Some(offset);
            }
            offset += match &f.ty {
                TypeRef::Primitive(t) => t.size(),
                TypeRef::Nested(n) => *self.sizes.get(n)?,
            } * f.copies();
        }
        None
    }

    /// Appends `fields` at `offset` under `prefix` until `out` holds its
    /// limit; returns the end offset.
    fn push_fields(
        &self,
        fields: &[RawField],
        prefix: &str,
        mut offset: usize,
        depth: usize,
        out: &mut (&mut Vec<FlatField>, usize),
    ) -> usize {
        for f in fields {
            for k in 0..f.copies() {
                if out.0.len() >= out.1 {
                    return offset;
                }
                let name = match f.count {
                    Some(_) => format!("{prefix}{}[{k}]", f.name),
                    None => format!("{prefix}{}", f.name),
                };
                offset = match &f.ty {
                    TypeRef::Primitive(t) => {
                        if !f.is_padding() {
                            out.0.push(FlatField {
                                name,
                                ty: *t,
                                offset,
                            });
                        }
                        offset + t.size()
                    }
                    TypeRef::Nested(n) => match self.defs.get(n) {
                        Some(def) if depth < MAX_NESTING => self.push_fields(
                            &def.fields,
                            &format!("{name}."),
                            offset,
                            depth + 1,
                            out,
                        ),
                        _ => offset,
                    },
                };
            }
        }
        offset
    }
}
