//! What a fit chose, and why: the window's signals, the network input and
//! prediction smoother among their candidates, one centre selection or
//! several, and how far each network was kept. The report a model stores
//! ([`crate::fit`] makes it, the model keeps it).

use crate::input::ModelInput;
use crate::smoother::Smoother;
use crate::window::signal_choice::WindowSignalsChoice;
use serde::{Deserialize, Serialize};

/// One candidate of a choice, as judged on the validation rows.
///
/// Two candidates are equal when every figure is, a NaN (not judged) equal
/// to a NaN: a report read back from a model file equals the one written.
#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct Candidate {
    /// The network's input.
    pub input: ModelInput,
    /// The prediction smoother.
    pub smoother: Option<Smoother>,
    /// Validation rms per channel (the filtered target against the
    /// prediction), in the target's unit, the sensor's channel order.
    pub val_rms: Vec<f64>,
    /// Their mean: what the choice minimises.
    pub mean_val_rms: f64,
    /// Largest ADEV after / ADEV before over τ, channels and runs (NaN
    /// when no run was long enough; `null` in a model file, read back as NaN).
    #[serde(deserialize_with = "nan_when_null")]
    pub worst_adev_ratio: f64,
    /// The channel where it was.
    pub worst_channel: String,
    /// The τ where it was, s (NaN, `null` in a file, when not judged).
    #[serde(deserialize_with = "nan_when_null")]
    pub worst_tau_s: f64,
    /// Largest ratio of ADEV after to its bound, before × (1 + hw68): at
    /// most 1 for a candidate that passes.
    #[serde(deserialize_with = "nan_when_null")]
    pub worst_excess: f64,
    /// True when ADEV after stays within its bound everywhere.
    pub passes: bool,
}

impl PartialEq for Candidate {
    fn eq(&self, other: &Self) -> bool {
        let same = |a: f64, b: f64| a == b || (a.is_nan() && b.is_nan());
        self.input == other.input
            && self.smoother == other.smoother
            && self.val_rms.len() == other.val_rms.len()
            && self
                .val_rms
                .iter()
                .zip(&other.val_rms)
                .all(|(a, b)| same(*a, *b))
            && same(self.mean_val_rms, other.mean_val_rms)
            && same(self.worst_adev_ratio, other.worst_adev_ratio)
            && self.worst_channel == other.worst_channel
            && same(self.worst_tau_s, other.worst_tau_s)
            && same(self.worst_excess, other.worst_excess)
            && self.passes == other.passes
    }
}

/// What a fit chose and why: every candidate's figures.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ChoiceReport {
    /// The candidates, inputs outer, smoothers inner.
    pub candidates: Vec<Candidate>,
    /// Index of the chosen one.
    pub chosen: usize,
    /// Validation runs whose ADEV was checked (0: the choice is by rms only).
    pub adev_runs: usize,
    /// The channels whose network keeps less than all of its output after
    /// the choice (`CHANNEL to zero: …` or `CHANNEL × SHARE: …`), each with
    /// why (it added variation on a record's validation rows, did not lower
    /// the validation rms, or raised a channel's or residue's bias
    /// instability: `sysid::fit`'s keep step); empty when none was.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub networks_shrunk: Vec<String>,
    /// On a large record, the input was chosen on a sample of it
    /// (`sysid::fit`'s input sample) and only that input was fitted on the
    /// whole record: the sample's rows and its candidates (every input and
    /// smoother). `candidates` then holds the chosen input's only. Absent
    /// when every input was fitted on the whole record.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub input_sample: Option<InputSample>,
    /// A channel's or residue's bias instability that compensation raises
    /// on a record and the keep step left so, with why (lowering the
    /// networks that raise it would cost their channels validation rms
    /// beyond its interval); empty when none was.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub bias_instability_raised: Vec<String>,
    /// The window's signals chosen from the training records, with each
    /// signal's dynamic rms there (`--window-signals auto`,
    /// [`crate::window::signal_choice`]): one choice for every channel, or
    /// one per group of channels that choose among their own signals
    /// ([`crate::window::signal_choice::choose_per_channel`]); empty when the
    /// recipe named them. In a file one choice is an object, several a list.
    #[serde(default, skip_serializing_if = "Vec::is_empty", with = "one_or_many")]
    pub window_signals: Vec<WindowSignalsChoice>,
}

/// The window-signal choices as a file holds them: one as an object (every
/// file written before channels chose apart), several as a list. Any other
/// shape is refused naming the key and both shapes, and an error inside a
/// choice is that choice's, said with the key.
mod one_or_many {
    use crate::window::signal_choice::WindowSignalsChoice;
    use serde::de::value::{MapAccessDeserializer, SeqAccessDeserializer};
    use serde::de::{Error, MapAccess, SeqAccess, Visitor};
    use serde::{Deserialize, Deserializer, Serialize, Serializer};

    pub fn serialize<S: Serializer>(v: &[WindowSignalsChoice], s: S) -> Result<S::Ok, S::Error> {
        match v {
            [one] => one.serialize(s),
            many => many.serialize(s),
        }
    }

    pub fn deserialize<'de, D: Deserializer<'de>>(
        d: D,
    ) -> Result<Vec<WindowSignalsChoice>, D::Error> {
        d.deserialize_any(OneOrMany)
    }

    struct OneOrMany;

    /// What the key holds, as an error says it.
    const SHAPES: &str = "`window_signals` to hold one window-signal choice (an object with unit, vibrates_at, records, signals, taken, rule) or a list of them, one per group of channels choosing among their own signals";

    impl<'de> Visitor<'de> for OneOrMany {
        type Value = Vec<WindowSignalsChoice>;

        fn expecting(&self, f: &mut std::fmt::Formatter) -> std::fmt::Result {
            f.write_str(SHAPES)
        }

        fn visit_map<A: MapAccess<'de>>(self, map: A) -> Result<Self::Value, A::Error> {
            WindowSignalsChoice::deserialize(MapAccessDeserializer::new(map))
                .map(|one| vec![one])
                .map_err(|e| A::Error::custom(format!("window_signals: {e}")))
        }

        fn visit_seq<A: SeqAccess<'de>>(self, seq: A) -> Result<Self::Value, A::Error> {
            Vec::deserialize(SeqAccessDeserializer::new(seq))
                .map_err(|e| A::Error::custom(format!("window_signals: {e}")))
        }
    }
}

/// The sample of a large record a choice of input was made on.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct InputSample {
    /// Rows of the sample (windows, in every chunk together).
    pub rows: usize,
    /// Chunks of contiguous rows, spread over the record.
    pub chunks: usize,
    /// Every candidate as judged on the sample, inputs outer, smoothers inner.
    pub candidates: Vec<Candidate>,
    /// Index of the one chosen there (its input was then fitted on the record).
    pub chosen: usize,
    /// The sample fitted again with one centre selection for every channel
    /// (the chosen input, every smoother), and whether the record was then
    /// fitted so. Absent when the recipe asked for one selection itself.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub shared_centres: Option<SharedCentresTrial>,
}

/// One centre selection for every channel against one per channel, as
/// judged on a large record's sample.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct SharedCentresTrial {
    /// The chosen candidate's mean validation rms with a selection per
    /// channel, in the target's unit.
    pub per_channel_mean_val_rms: f64,
    /// The same with one selection for all channels.
    pub shared_mean_val_rms: f64,
    /// True when the record was fitted with one selection: its mean
    /// validation rms on the sample is within `sysid::fit`'s
    /// `SHARED_CENTRES_TOLERANCE` of the per-channel one's, and it keeps
    /// the Allan deviation within its bound if the per-channel one does.
    pub taken: bool,
}

impl Candidate {
    /// A candidate with its validation rms per channel and no run judged
    /// by ADEV yet (ratios NaN, passing).
    pub fn unjudged(input: ModelInput, smoother: Option<Smoother>, val_rms: Vec<f64>) -> Self {
        Self {
            input,
            smoother,
            mean_val_rms: stats::mean(&val_rms),
            val_rms,
            worst_adev_ratio: f64::NAN,
            worst_channel: String::new(),
            worst_tau_s: f64::NAN,
            worst_excess: 0.0,
            passes: true,
        }
    }
}

impl ChoiceReport {
    /// The chosen candidate.
    pub fn chosen(&self) -> &Candidate {
        &self.candidates[self.chosen]
    }

    /// The candidate of the paper's model: raw window, no smoother (the
    /// baseline the choice's cost and gain are told against).
    pub fn baseline(&self) -> Option<&Candidate> {
        self.candidates
            .iter()
            .find(|c| c.input == ModelInput::Raw && c.smoother.is_none())
    }
}

/// A number that JSON writes as `null` when it is NaN (serde_json has no
/// NaN), read back as NaN, so a model whose choice judged no ADEV loads.
fn nan_when_null<'de, D: serde::Deserializer<'de>>(d: D) -> Result<f64, D::Error> {
    Ok(Option::<f64>::deserialize(d)?.unwrap_or(f64::NAN))
}
