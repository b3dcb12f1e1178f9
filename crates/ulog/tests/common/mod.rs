//! A minimal ULog writer for the tests: every message kind, laid out as
//! the specification and PX4's logger lay them out, so each reader rule can
//! be exercised on a file built for it.

#![allow(dead_code)]

/// A ULog file under construction.
pub struct Writer {
    pub bytes: Vec<u8>,
}

/// Where the flag-bits message's appended offsets are.
const OFFSETS_AT: usize = 16 + 3 + 16;

impl Writer {
    /// Header (version 1, start 1000 µs) and flag bits; `appended` sets
    /// incompat bit 0 (data appended).
    pub fn new(appended: bool) -> Self {
        let mut w = Self::without_flags();
        let mut p = vec![0u8; 40];
        if appended {
            p[8] = 1;
        }
        w.msg(b'B', &p);
        w
    }

    /// Header only (old logs have no flag bits).
    pub fn without_flags() -> Self {
        let mut bytes = vec![0x55, 0x4c, 0x6f, 0x67, 0x01, 0x12, 0x35, 1];
        bytes.extend_from_slice(&1000u64.to_le_bytes());
        Self { bytes }
    }

    pub fn msg(&mut self, kind: u8, payload: &[u8]) -> &mut Self {
        self.bytes
            .extend_from_slice(&(payload.len() as u16).to_le_bytes());
        self.bytes.push(kind);
        self.bytes.extend_from_slice(payload);
        self
    }

    pub fn format(&mut self, text: &str) -> &mut Self {
        self.msg(b'F', text.as_bytes())
    }

    fn keyed(key: &str, value: &[u8]) -> Vec<u8> {
        let mut p = vec![key.len() as u8];
        p.extend_from_slice(key.as_bytes());
        p.extend_from_slice(value);
        p
    }

    pub fn info(&mut self, typed_key: &str, value: &[u8]) -> &mut Self {
        self.msg(b'I', &Self::keyed(typed_key, value))
    }

    pub fn multi_info(&mut self, continued: bool, typed_key: &str, value: &[u8]) -> &mut Self {
        let mut p = vec![continued as u8];
        p.extend(Self::keyed(typed_key, value));
        self.msg(b'M', &p)
    }

    pub fn parameter_f32(&mut self, name: &str, v: f32) -> &mut Self {
        self.msg(
            b'P',
            &Self::keyed(&format!("float {name}"), &v.to_le_bytes()),
        )
    }

    pub fn parameter_i32(&mut self, name: &str, v: i32) -> &mut Self {
        self.msg(
            b'P',
            &Self::keyed(&format!("int32_t {name}"), &v.to_le_bytes()),
        )
    }

    pub fn subscribe(&mut self, instance: u8, msg_id: u16, topic: &str) -> &mut Self {
        let mut p = vec![instance];
        p.extend_from_slice(&msg_id.to_le_bytes());
        p.extend_from_slice(topic.as_bytes());
        self.msg(b'A', &p)
    }

    pub fn remove(&mut self, msg_id: u16) -> &mut Self {
        self.msg(b'R', &msg_id.to_le_bytes())
    }

    pub fn data(&mut self, msg_id: u16, sample: &[u8]) -> &mut Self {
        let mut p = msg_id.to_le_bytes().to_vec();
        p.extend_from_slice(sample);
        self.msg(b'D', &p)
    }

    pub fn dropout(&mut self, ms: u16) -> &mut Self {
        self.msg(b'O', &ms.to_le_bytes())
    }

    pub fn sync(&mut self) -> &mut Self {
        self.msg(b'S', &[0x2f, 0x73, 0x13, 0x20, 0x25, 0x0c, 0xbb, 0x12])
    }

    pub fn logging(&mut self, level: u8, t: u64, text: &str) -> &mut Self {
        let mut p = vec![level];
        p.extend_from_slice(&t.to_le_bytes());
        p.extend_from_slice(text.as_bytes());
        self.msg(b'L', &p)
    }

    pub fn tagged(&mut self, level: u8, tag: u16, t: u64, text: &str) -> &mut Self {
        let mut p = vec![level];
        p.extend_from_slice(&tag.to_le_bytes());
        p.extend_from_slice(&t.to_le_bytes());
        p.extend_from_slice(text.as_bytes());
        self.msg(b'C', &p)
    }

    /// Sets appended offset `k` (0–2) of the flag bits.
    pub fn set_appended_offset(&mut self, k: usize, offset: u64) -> &mut Self {
        let at = OFFSETS_AT + 8 * k;
        self.bytes[at..at + 8].copy_from_slice(&offset.to_le_bytes());
        self
    }

    pub fn len(&self) -> usize {
        self.bytes.len()
    }
}

/// The test topic's formats: a nested type, arrays, and trailing padding.
pub const VEC3: &str = "vec3:float x;float y;float z;";
pub const IMU: &str =
    "imu:uint64_t timestamp;float[3] gyro;int32_t rel;vec3 acc;uint8_t[3] _padding0;";
/// Bytes of an `imu` sample without / with its trailing padding.
pub const IMU_MIN: usize = 8 + 12 + 4 + 12;
pub const IMU_FULL: usize = IMU_MIN + 3;

/// An `imu` sample (without the trailing padding).
pub fn imu(t: u64, gyro: [f32; 3], rel: i32, acc: [f32; 3]) -> Vec<u8> {
    let mut s = t.to_le_bytes().to_vec();
    for g in gyro {
        s.extend_from_slice(&g.to_le_bytes());
    }
    s.extend_from_slice(&rel.to_le_bytes());
    for a in acc {
        s.extend_from_slice(&a.to_le_bytes());
    }
    s
}

/// A log with the `imu` topic at two instances (ids 1 and 2), `n` samples
/// each, instance 0 at 1000 + 4000 k µs with gyro (k, 2k, 3k) and acc
/// (k/2, 0, −9.8), instance 1 at 3000 + 4000 k µs with gyro −k; info,
/// parameters, logged strings, a dropout and a sync between them.
pub fn two_imus(n: usize) -> Writer {
    let mut w = Writer::new(false);
    w.format(VEC3).format(IMU);
    w.info("char[4] sys_name", b"PX4!")
        .info("int32_t ver_hw_id", &7i32.to_le_bytes());
    w.multi_info(false, "char[3] perf", b"one")
        .multi_info(true, "char[3] perf", b"two");
    w.parameter_f32("IMU_GYRO_CUTOFF", 30.0)
        .parameter_i32("SDLOG_MODE", 1);
    w.subscribe(0, 1, "imu").subscribe(1, 2, "imu");
    w.logging(b'6', 500, "logging started");
    for k in 0..n {
        let f = k as f32;
        w.data(
            1,
            &imu(
                1000 + 4000 * k as u64,
                [f, 2.0 * f, 3.0 * f],
                0,
                [f / 2.0, 0.0, -9.8],
            ),
        );
        w.data(2, &imu(3000 + 4000 * k as u64, [-f, 0.0, 0.0], 0, [0.0; 3]));
        if k == n / 2 {
            w.dropout(25).sync().parameter_f32("IMU_GYRO_CUTOFF", 40.0);
            w.tagged(b'4', 3, 1000 + 4000 * k as u64, "tagged");
        }
    }
    w
}
