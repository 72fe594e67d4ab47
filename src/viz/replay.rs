//! Recordings compared value by value: `drape replay` runs a session again and checks the
//! new logged data against the stored recording, chunk by chunk in order (entity, static
//! or not, timelines, components), then row by row and value by value, floats within a
//! tolerance that defaults to exact; the first difference is named by step, stage, entity,
//! component, row and index. A digest of the same canonical data stands in for a recording
//! too large to keep.

use std::collections::BTreeMap;
use std::fmt;
use std::path::Path;

use rerun::external::arrow::array::{Array, AsArray};
use rerun::external::arrow::datatypes::{self as adt, DataType};
use rerun::external::re_log_encoding::DecoderApp;
use rerun::log::{Chunk, LogMsg};

/// One logged value, flattened out of its Arrow array.
#[derive(Clone, Debug, PartialEq)]
pub enum Value {
    /// Any number (floats, integers, booleans as 0 / 1).
    Num(f64),
    /// Text.
    Text(String),
    /// A null slot.
    Null,
}

impl fmt::Display for Value {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::Num(v) => write!(f, "{v}"),
            Self::Text(t) => write!(f, "{t:?}"),
            Self::Null => f.write_str("null"),
        }
    }
}

/// A chunk of a recording, ids left out: what two runs of a session must agree on.
#[derive(Clone, Debug, PartialEq)]
pub struct FlatChunk {
    /// Entity path.
    pub entity: String,
    /// Static (no timeline).
    pub is_static: bool,
    /// Time of each row on each timeline, by timeline name.
    pub times: BTreeMap<String, Vec<i64>>,
    /// Per component (sorted by name), each row's values (`None`: the row has none).
    pub components: BTreeMap<String, Vec<Option<Vec<Value>>>>,
}

/// Why a recording could not be read.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum ReplayError {
    /// The file could not be read.
    #[error("{path}: cannot read: {source}")]
    Read {
        /// The file.
        path: String,
        /// The cause.
        #[source]
        source: std::io::Error,
    },
    /// The file is not a whole recording.
    #[error("{path}: not a readable recording: {detail}")]
    Decode {
        /// The file.
        path: String,
        /// What the decoder said.
        detail: String,
    },
}

/// Appends `value(i)` for each row `i` of `array` to `out`, `Null` for null rows.
fn push_rows(out: &mut Vec<Value>, array: &dyn Array, value: impl Fn(usize) -> Value) {
    out.extend((0..array.len()).map(|i| if array.is_null(i) { Value::Null } else { value(i) }));
}

/// Appends the values of `array` (recursively through lists and structs) to `out`.
fn flatten(array: &dyn Array, out: &mut Vec<Value>) {
    macro_rules! prim {
        ($t:ty) => {{
            let a = array.as_primitive::<$t>();
            push_rows(out, array, |i| Value::Num(a.value(i) as f64));
        }};
    }
    match array.data_type() {
        DataType::Float32 => prim!(adt::Float32Type),
        DataType::Float64 => prim!(adt::Float64Type),
        DataType::Int8 => prim!(adt::Int8Type),
        DataType::Int16 => prim!(adt::Int16Type),
        DataType::Int32 => prim!(adt::Int32Type),
        DataType::Int64 => prim!(adt::Int64Type),
        DataType::UInt8 => prim!(adt::UInt8Type),
        DataType::UInt16 => prim!(adt::UInt16Type),
        DataType::UInt32 => prim!(adt::UInt32Type),
        DataType::UInt64 => prim!(adt::UInt64Type),
        DataType::Boolean => {
            let a = array.as_boolean();
            push_rows(out, array, |i| Value::Num(f64::from(u8::from(a.value(i)))));
        }
        DataType::Utf8 => {
            let a = array.as_string::<i32>();
            push_rows(out, array, |i| Value::Text(a.value(i).to_string()));
        }
        DataType::LargeUtf8 => {
            let a = array.as_string::<i64>();
            push_rows(out, array, |i| Value::Text(a.value(i).to_string()));
        }
        DataType::FixedSizeList(..) | DataType::List(_) => {
            for i in 0..array.len() {
                if array.is_null(i) {
                    out.push(Value::Null);
                } else if let Some(a) = array.as_fixed_size_list_opt() {
                    flatten(a.value(i).as_ref(), out);
                } else if let Some(a) = array.as_list_opt::<i32>() {
                    flatten(a.value(i).as_ref(), out);
                }
            }
        }
        DataType::Struct(_) => {
            let a = array.as_struct();
            for i in 0..a.len() {
                for column in a.columns() {
                    flatten(column.slice(i, 1).as_ref(), out);
                }
            }
        }
        // Anything else (unions, binary blobs): compared as its printed form.
        _ => out.push(Value::Text(format!("{array:?}"))),
    }
}

/// The recording's chunks (its data, not the blueprint), flattened, in order.
pub fn flatten_messages(msgs: impl IntoIterator<Item = LogMsg>) -> Vec<FlatChunk> {
    let mut out = Vec::new();
    for msg in msgs {
        let LogMsg::ArrowMsg(store, arrow) = msg else { continue };
        if store.kind() != rerun::StoreKind::Recording {
            continue;
        }
        let Ok(chunk) = Chunk::from_arrow_msg(&arrow) else {
            continue;
        };
        out.push(flatten_chunk(&chunk));
    }
    out
}

fn flatten_chunk(chunk: &Chunk) -> FlatChunk {
    let times = chunk
        .timelines()
        .iter()
        .map(|(name, column)| (name.to_string(), column.times_raw().to_vec()))
        .collect();
    let components = chunk
        .components()
        .values()
        .map(|column| {
            let list = &column.list_array;
            let rows = (0..list.len())
                .map(|i| {
                    (!list.is_null(i)).then(|| {
                        let mut values = Vec::new();
                        flatten(list.value(i).as_ref(), &mut values);
                        values
                    })
                })
                .collect();
            (column.descriptor.component.to_string(), rows)
        })
        .collect();
    FlatChunk {
        entity: chunk.entity_path().to_string(),
        is_static: chunk.is_static(),
        times,
        components,
    }
}

/// Reads an `.rrd` file whole (every message must decode).
pub fn read_rrd(path: &Path) -> Result<Vec<FlatChunk>, ReplayError> {
    let name = path.display().to_string();
    let bytes = std::fs::read(path).map_err(|source| ReplayError::Read {
        path: name.clone(),
        source,
    })?;
    let decoder = DecoderApp::decode_eager(bytes.as_slice()).map_err(|e| ReplayError::Decode {
        path: name.clone(),
        detail: e.to_string(),
    })?;
    let msgs = decoder
        .collect::<Result<Vec<LogMsg>, _>>()
        .map_err(|e| ReplayError::Decode {
            path: name,
            detail: e.to_string(),
        })?;
    Ok(flatten_messages(msgs))
}

/// Where two recordings first differ.
#[derive(Clone, Debug, PartialEq)]
pub struct Difference {
    /// Chunk index (in write order).
    pub chunk: usize,
    /// Entity path.
    pub entity: String,
    /// The `step` and `stage` of the row, where known.
    pub step: Option<i64>,
    /// The `stage` timeline's value.
    pub stage: Option<i64>,
    /// Component, where the difference is in one.
    pub component: Option<String>,
    /// Row in the chunk and index in the row's values.
    pub row: Option<usize>,
    /// Index in the row's values.
    pub index: Option<usize>,
    /// What differs.
    pub detail: String,
}

impl fmt::Display for Difference {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "chunk {}", self.chunk)?;
        if let Some(s) = self.step {
            write!(f, ", step {s}")?;
        }
        if let Some(s) = self.stage {
            write!(f, ", stage {s}")?;
        }
        write!(f, ", entity {}", self.entity)?;
        if let Some(c) = &self.component {
            write!(f, ", component {c}")?;
        }
        if let Some(r) = self.row {
            write!(f, ", row {r}")?;
        }
        if let Some(i) = self.index {
            write!(f, ", index {i}")?;
        }
        write!(f, ": {}", self.detail)
    }
}

/// The first difference between `stored` and `new` (chunk order counts), floats equal when
/// `|a - b| <= tolerance` (0: exact); `None` when they agree.
pub fn first_difference(stored: &[FlatChunk], new: &[FlatChunk], tolerance: f64) -> Option<Difference> {
    for (k, (a, b)) in stored.iter().zip(new).enumerate() {
        let at = |row: Option<usize>| {
            let time = |name: &str| row.and_then(|r| a.times.get(name).and_then(|t| t.get(r).copied()));
            (time("step"), time("stage"))
        };
        let diff = |row: Option<usize>, component: Option<&str>, index: Option<usize>, detail: String| {
            let (step, stage) = at(row.or(Some(0)));
            Some(Difference {
                chunk: k,
                entity: a.entity.clone(),
                step,
                stage,
                component: component.map(str::to_string),
                row,
                index,
                detail,
            })
        };
        if a.entity != b.entity {
            return diff(None, None, None, format!("entity {} here, {} now", a.entity, b.entity));
        }
        if a.is_static != b.is_static || a.times != b.times {
            return diff(None, None, None, "different timelines or times".into());
        }
        let names_a: Vec<&String> = a.components.keys().collect();
        let names_b: Vec<&String> = b.components.keys().collect();
        if names_a != names_b {
            return diff(
                None,
                None,
                None,
                format!("components {names_a:?} here, {names_b:?} now"),
            );
        }
        for (name, rows_a) in &a.components {
            let rows_b = &b.components[name];
            for (r, (x, y)) in rows_a.iter().zip(rows_b).enumerate() {
                match (x, y) {
                    (Some(x), Some(y)) => {
                        if x.len() != y.len() {
                            return diff(
                                Some(r),
                                Some(name),
                                None,
                                format!("{} values here, {} now", x.len(), y.len()),
                            );
                        }
                        for (i, (u, v)) in x.iter().zip(y).enumerate() {
                            let same = match (u, v) {
                                (Value::Num(p), Value::Num(q)) => {
                                    p.to_bits() == q.to_bits() || (p - q).abs() <= tolerance
                                }
                                _ => u == v,
                            };
                            if !same {
                                return diff(Some(r), Some(name), Some(i), format!("{u} here, {v} now"));
                            }
                        }
                    }
                    (None, None) => {}
                    _ => return diff(Some(r), Some(name), None, "a row with no data on one side".into()),
                }
            }
        }
    }
    (stored.len() != new.len()).then(|| Difference {
        chunk: stored.len().min(new.len()),
        entity: String::new(),
        step: None,
        stage: None,
        component: None,
        row: None,
        index: None,
        detail: format!("{} chunks here, {} now", stored.len(), new.len()),
    })
}

/// A digest of the recording's data (64-bit FNV-1a over the canonical flattened form:
/// entities, timelines, components and every value's bits), as 16 hex digits.
pub fn digest(chunks: &[FlatChunk]) -> String {
    let mut h: u64 = 0xcbf2_9ce4_8422_2325;
    let mut eat = |bytes: &[u8]| {
        for b in bytes {
            h ^= u64::from(*b);
            h = h.wrapping_mul(0x0100_0000_01b3);
        }
    };
    for c in chunks {
        eat(c.entity.as_bytes());
        eat(&[u8::from(c.is_static)]);
        for (name, times) in &c.times {
            eat(name.as_bytes());
            times.iter().for_each(|t| eat(&t.to_le_bytes()));
        }
        for (name, rows) in &c.components {
            eat(name.as_bytes());
            for row in rows {
                match row {
                    None => eat(b"-"),
                    Some(values) => {
                        eat(&(values.len() as u64).to_le_bytes());
                        for v in values {
                            match v {
                                Value::Num(x) => eat(&x.to_bits().to_le_bytes()),
                                Value::Text(t) => eat(t.as_bytes()),
                                Value::Null => eat(b"0"),
                            }
                        }
                    }
                }
            }
        }
    }
    format!("{h:016x}")
}
