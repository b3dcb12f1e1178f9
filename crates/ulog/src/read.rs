//! Reading a file: the header and flag bits, the definitions section
//! (formats, info, parameters) and the data section (subscriptions, data,
//! logged strings, dropouts, syncs), then each appended data section, the
//! way pyulog reads them: a message that runs past the start of the next
//! section is dropped, a message cut by the end of the file ends the read.

use std::collections::HashMap;
use std::path::Path;

use crate::bytes::{Cursor, at};
use crate::error::{UlogError, shorten};
use crate::format::{Formats, parse_format};
use crate::messages;
use crate::model::{Dropout, Header, Integrity, ParameterChange, TopicData, Ulog};

/// The first 7 bytes of every ULog file.
const MAGIC: [u8; 7] = [0x55, 0x4c, 0x6f, 0x67, 0x01, 0x12, 0x35];
/// The payload of a sync (`S`) message.
const SYNC: [u8; 8] = [0x2f, 0x73, 0x13, 0x20, 0x25, 0x0c, 0xbb, 0x12];
/// A message header of an unknown type with a larger payload is taken as
/// damage, as pyulog takes it.
const MAX_UNKNOWN_PAYLOAD: usize = 10_000;
/// Incompatible flag 0, bit 0: data appended.
const DATA_APPENDED: u8 = 1;

impl Ulog {
    /// Reads a `.ulg` file.
    pub fn read(path: impl AsRef<Path>) -> Result<Self, UlogError> {
        let file = path.as_ref().display().to_string();
        let bytes = std::fs::read(path.as_ref()).map_err(|source| UlogError::Io {
            file: file.clone(),
            source,
        })?;
        Self::parse(&bytes, &file)
    }

    /// Reads a log from memory; `file` names it in errors.
    pub fn parse(bytes: &[u8], file: &str) -> Result<Self, UlogError> {
        let mut reader = Reader::new(file);
        reader.run(bytes)?;
        Ok(reader.log)
    }
}

/// One message: its type, payload and where the next one starts.
struct Message<'a> {
    kind: u8,
    payload: &'a [u8],
    next: usize,
}

/// The message at `pos`, or `None` if `bytes` ends inside it.
fn message_at(bytes: &[u8], pos: usize) -> Option<Message<'_>> {
    let mut c = Cursor::new(bytes.get(pos..)?);
    let size = c.u16()? as usize;
    let kind = c.u8()?;
    let payload = c.take(size)?;
    Some(Message {
        kind,
        payload,
        next: pos + 3 + size,
    })
}

/// What to do after a message.
enum Step {
    Next,
    /// The header looked damaged: search for a sync marker.
    Resync,
}

struct Reader {
    log: Ulog,
    /// Message id → index into `log.topics`.
    subscriptions: HashMap<u16, usize>,
    /// (topic, instance) → index into `log.topics`.
    topic_index: HashMap<(String, u8), usize>,
    in_data: bool,
    /// The latest data time stamp seen, µs (dropouts and parameter changes
    /// are placed after it, as pyulog places them).
    last_us: u64,
}

impl Reader {
    fn new(file: &str) -> Self {
        Self {
            log: Ulog {
                file: file.to_string(),
                header: Header::default(),
                formats: Formats::default(),
                topics: Vec::new(),
                info: Default::default(),
                multi_info: Default::default(),
                parameters: Default::default(),
                parameter_changes: Vec::new(),
                logged: Vec::new(),
                integrity: Integrity::default(),
            },
            subscriptions: HashMap::new(),
            topic_index: HashMap::new(),
            in_data: false,
            last_us: 0,
        }
    }

    fn file(&self) -> String {
        self.log.file.clone()
    }

    fn run(&mut self, bytes: &[u8]) -> Result<(), UlogError> {
        if bytes.len() < 16 {
            return Err(UlogError::TooShort {
                file: self.file(),
                len: bytes.len(),
            });
        }
        if bytes[..7] != MAGIC {
            return Err(UlogError::NotUlog { file: self.file() });
        }
        self.log.header.version = bytes[7];
        self.log.header.start_us = at(bytes, 8).map_or(0, u64::from_le_bytes);
        let mut pos = 16;
        if let Some(m) = message_at(bytes, pos).filter(|m| m.kind == b'B') {
            self.flag_bits(m.payload, pos)?;
            pos = m.next;
        }
        let sections = self.sections(bytes.len(), pos)?;
        let last = sections.len() - 1;
        for (k, &(start, end)) in sections.iter().enumerate() {
            if k > 0 {
                self.log.integrity.appended_sections += 1;
            }
            self.section(&bytes[..end], start, k == last)?;
        }
        Ok(())
    }

    fn flag_bits(&mut self, payload: &[u8], offset: usize) -> Result<(), UlogError> {
        let flags = messages::flag_bits(payload).ok_or(UlogError::FlagBits {
            file: self.file(),
            offset,
            len: payload.len(),
        })?;
        let known = [!DATA_APPENDED, 0xff, 0xff, 0xff, 0xff, 0xff, 0xff, 0xff];
        if let Some(index) = (0..8).find(|&i| flags.incompat[i] & known[i] != 0) {
            return Err(UlogError::Incompatible {
                file: self.file(),
                index,
                value: flags.incompat[index],
            });
        }
        let h = &mut self.log.header;
        h.compat_flags = flags.compat;
        h.incompat_flags = flags.incompat;
        if flags.incompat[0] & DATA_APPENDED != 0 {
            h.appended_offsets = flags
                .appended_offsets
                .into_iter()
                .filter(|&o| o != 0)
                .collect();
        }
        Ok(())
    }

    /// The byte ranges to read: from `start` to the first appended offset,
    /// then each appended section to the next or to the end.
    fn sections(&self, len: usize, start: usize) -> Result<Vec<(usize, usize)>, UlogError> {
        let mut bounds = vec![start];
        for &o in &self.log.header.appended_offsets {
            let prev = *bounds.last().unwrap_or(&start);
            let reason = if o > len as u64 {
                Some(format!("is past the end of the file ({len} bytes)"))
            } else if (o as usize) < prev {
                Some(format!("is before the section it follows (byte {prev})"))
            } else {
                None
            };
            if let Some(reason) = reason {
                return Err(UlogError::AppendedOffset {
                    file: self.file(),
                    offset: o,
                    reason,
                });
            }
            bounds.push(o as usize);
        }
        bounds.push(len);
        Ok(bounds.windows(2).map(|w| (w[0], w[1])).collect())
    }

    /// Reads the messages of `bytes[start..]`.
    fn section(&mut self, bytes: &[u8], start: usize, last: bool) -> Result<(), UlogError> {
        let mut pos = start;
        while pos < bytes.len() {
            let Some(m) = message_at(bytes, pos) else {
                if last {
                    self.log.integrity.truncated = true;
                } else {
                    self.log.integrity.cut_messages += 1;
                }
                return Ok(());
            };
            match self.message(&m, pos)? {
                Step::Next => pos = m.next,
                Step::Resync => {
                    let from = pos + 1;
                    match bytes[from..].windows(SYNC.len()).position(|w| w == SYNC) {
                        Some(k) => {
                            self.log.integrity.skipped_bytes += k + 1;
                            self.log.integrity.syncs += 1;
                            pos = from + k + SYNC.len();
                        }
                        None => {
                            self.log.integrity.skipped_bytes += bytes.len() - pos;
                            return Ok(());
                        }
                    }
                }
            }
        }
        Ok(())
    }

    fn message(&mut self, m: &Message, offset: usize) -> Result<Step, UlogError> {
        if !self.in_data && matches!(m.kind, b'A' | b'L' | b'C' | b'D' | b'O' | b'S' | b'R') {
            self.in_data = true;
        }
        let ok = match (m.kind, self.in_data) {
            (b'F', false) => {
                let def = parse_format(m.payload).map_err(|reason| UlogError::Format {
                    file: self.file(),
                    offset,
                    reason,
                })?;
                self.log.formats.insert(def);
                true
            }
            (b'I', _) => self.info(m.payload),
            (b'M', _) => self.multi_info(m.payload),
            (b'P', _) => self.parameter(m.payload),
            (b'Q', _) => m.payload.len() > 1 && messages::info(&m.payload[1..]).is_some(),
            (b'A', _) => self.subscribe(m.payload, offset),
            (b'R', _) => self.unsubscribe(m.payload),
            (b'D', _) => self.data(m.payload),
            (b'L' | b'C', _) => self.logged(m.payload, m.kind == b'C'),
            (b'O', _) => self.dropout(m.payload),
            (b'S', _) => {
                self.log.integrity.syncs += 1;
                m.payload == SYNC
            }
            (kind, _) => {
                if kind == 0 || m.payload.is_empty() || m.payload.len() > MAX_UNKNOWN_PAYLOAD {
                    return Ok(Step::Resync);
                }
                self.log.integrity.unknown_messages += 1;
                true
            }
        };
        if !ok {
            self.log.integrity.corrupt_messages += 1;
        }
        Ok(Step::Next)
    }

    fn info(&mut self, payload: &[u8]) -> bool {
        let Some(i) = messages::info(payload) else {
            return false;
        };
        self.log.info.insert(i.key, i.value);
        true
    }

    fn multi_info(&mut self, payload: &[u8]) -> bool {
        let Some((continued, i)) = messages::multi_info(payload) else {
            return false;
        };
        let lists = self.log.multi_info.entry(i.key).or_default();
        match lists.last_mut() {
            Some(list) if continued => list.push(i.value),
            _ => lists.push(vec![i.value]),
        }
        true
    }

    fn parameter(&mut self, payload: &[u8]) -> bool {
        let Some((name, value)) = messages::parameter(payload) else {
            return false;
        };
        if self.in_data {
            self.log.parameter_changes.push(ParameterChange {
                after_us: self.last_us,
                name,
                value,
            });
        } else {
            self.log.parameters.insert(name, value);
        }
        true
    }

    fn subscribe(&mut self, payload: &[u8], offset: usize) -> bool {
        let Some(s) = messages::subscribe(payload) else {
            return false;
        };
        let layout = match self.log.formats.layout(&s.topic) {
            Ok(layout) => layout,
            Err(reason) => {
                self.subscriptions.remove(&s.msg_id);
                let why = format!("byte {offset}: '{}': {reason}", shorten(&s.topic));
                self.log.integrity.bad_subscriptions.push(why);
                return true;
            }
        };
        let key = (s.topic.clone(), s.instance);
        let index = match self.topic_index.get(&key) {
            Some(&index) => index,
            None => {
                self.log.topics.push(TopicData {
                    timestamp_offset: self.log.formats.timestamp_offset(&s.topic),
                    name: s.topic,
                    instance: s.instance,
                    layout,
                    bytes: Vec::new(),
                    count: 0,
                });
                self.topic_index.insert(key, self.log.topics.len() - 1);
                self.log.topics.len() - 1
            }
        };
        self.subscriptions.insert(s.msg_id, index);
        true
    }

    fn unsubscribe(&mut self, payload: &[u8]) -> bool {
        let Some(id) = Cursor::new(payload).u16() else {
            return false;
        };
        self.subscriptions.remove(&id);
        true
    }

    fn data(&mut self, payload: &[u8]) -> bool {
        let mut c = Cursor::new(payload);
        let Some(index) = c.u16().and_then(|id| self.subscriptions.get(&id).copied()) else {
            return false;
        };
        let sample = c.rest();
        let topic = &mut self.log.topics[index];
        let layout = topic.layout;
        if sample.len() < layout.min_size || sample.len() > layout.size {
            return false;
        }
        topic.bytes.extend_from_slice(&sample[..layout.min_size]);
        topic.count += 1;
        if let Some(t) = topic.timestamp_offset.and_then(|o| at(sample, o)) {
            self.last_us = self.last_us.max(u64::from_le_bytes(t));
        }
        true
    }

    fn logged(&mut self, payload: &[u8], tagged: bool) -> bool {
        let Some(m) = messages::logged(payload, tagged) else {
            return false;
        };
        self.log.logged.push(m);
        true
    }

    fn dropout(&mut self, payload: &[u8]) -> bool {
        let Some(duration_ms) = Cursor::new(payload).u16() else {
            return false;
        };
        self.log.integrity.dropouts.push(Dropout {
            after_us: self.last_us,
            duration_ms,
        });
        true
    }
}
