//! The payloads of the messages other than formats and data: flag bits,
//! info and parameters, subscriptions, logged strings. Each decoder returns
//! `None` for a payload too short or malformed for its fields.

use crate::bytes::Cursor;
use crate::format::FieldType;
use crate::model::InfoValue;

/// The flag-bits message (`B`).
pub(crate) struct FlagBits {
    pub compat: [u8; 8],
    pub incompat: [u8; 8],
    pub appended_offsets: [u64; 3],
}

pub(crate) fn flag_bits(payload: &[u8]) -> Option<FlagBits> {
    let mut c = Cursor::new(payload);
    Some(FlagBits {
        compat: c.array()?,
        incompat: c.array()?,
        appended_offsets: [c.u64()?, c.u64()?, c.u64()?],
    })
}

/// An info or parameter payload: `key_len`, `"type name"`, value.
pub(crate) struct Info {
    pub key: String,
    pub value: InfoValue,
}

pub(crate) fn info(payload: &[u8]) -> Option<Info> {
    let mut c = Cursor::new(payload);
    let key_len = c.u8()? as usize;
    let typed_key = std::str::from_utf8(c.take(key_len)?).ok()?;
    let (ty, key) = typed_key.split_once(' ')?;
    let raw = c.rest();
    let value = if ty.starts_with("char[") {
        InfoValue::Text(String::from_utf8_lossy(raw).into_owned())
    } else {
        match FieldType::parse(ty) {
            Some(t) if raw.len() != t.size() => return None,
            Some(t) if t.is_integer() => InfoValue::Integer(t.decode_integer(raw, 0)?),
            Some(t @ (FieldType::Float | FieldType::Double)) => InfoValue::Float(t.decode(raw, 0)?),
            _ => InfoValue::Bytes(raw.to_vec()),
        }
    };
    Some(Info {
        key: key.to_string(),
        value,
    })
}

/// A multi-info payload (`M`): `is_continued`, then an info payload.
pub(crate) fn multi_info(payload: &[u8]) -> Option<(bool, Info)> {
    let (&continued, rest) = payload.split_first()?;
    Some((continued != 0, info(rest)?))
}

/// A parameter (`P`): an info payload of an `int32_t` or a `float`.
pub(crate) fn parameter(payload: &[u8]) -> Option<(String, f64)> {
    let Info { key, value } = info(payload)?;
    match value {
        InfoValue::Integer(v) => Some((key, v as f64)),
        InfoValue::Float(v) => Some((key, v)),
        _ => None,
    }
}

/// A subscription (`A`): multi-instance id, message id, topic name.
pub(crate) struct Subscribe {
    pub instance: u8,
    pub msg_id: u16,
    pub topic: String,
}

pub(crate) fn subscribe(payload: &[u8]) -> Option<Subscribe> {
    let mut c = Cursor::new(payload);
    let instance = c.u8()?;
    let msg_id = c.u16()?;
    let topic = std::str::from_utf8(c.rest()).ok()?;
    (!topic.is_empty()).then(|| Subscribe {
        instance,
        msg_id,
        topic: topic.to_string(),
    })
}

/// A logged string (`L`), or a tagged one (`C`) when `tagged`.
pub(crate) fn logged(payload: &[u8], tagged: bool) -> Option<crate::model::LoggedMessage> {
    let mut c = Cursor::new(payload);
    let level = c.u8()?;
    let tag = if tagged { Some(c.u16()?) } else { None };
    let timestamp_us = c.u64()?;
    Some(crate::model::LoggedMessage {
        level,
        tag,
        timestamp_us,
        text: String::from_utf8_lossy(c.rest()).into_owned(),
    })
}
