//! One PLY element (a vertex, a face) as `ply-rs-bw` reads and writes it, kept compact.
//!
//! The crate's own element is a map from property name to value that allocates each name
//! again for every element; a 50,000-vertex file with eleven properties a vertex spent most
//! of its reading there. [`Row`] keeps the values in the header's order, each beside a hash
//! of its name (FNV-1a), so that reading and writing an element allocates once. The names
//! of one element's properties are checked to hash apart before a file is read.

use ply_rs_bw::ply::{Property, PropertyAccess};

/// The 64-bit FNV-1a hash of a property name.
pub(super) fn name_hash(name: &str) -> u64 {
    name.bytes().fold(0xcbf2_9ce4_8422_2325, |h, b| {
        (h ^ u64::from(b)).wrapping_mul(0x0000_0100_0000_01b3)
    })
}

/// An element's values in the header's order, each with its name's hash.
#[derive(Clone, Debug, Default, PartialEq)]
pub(super) struct Row(Vec<(u64, Property)>);

impl Row {
    /// The value of property `name`.
    pub(super) fn get(&self, name: &str) -> Option<&Property> {
        let key = name_hash(name);
        self.0.iter().find(|(k, _)| *k == key).map(|(_, p)| p)
    }
}

macro_rules! scalar {
    ($name:ident, $variant:ident, $t:ty) => {
        fn $name(&self, name: &str) -> Option<$t> {
            match self.get(name)? {
                Property::$variant(v) => Some(*v),
                _ => None,
            }
        }
    };
}

macro_rules! list {
    ($name:ident, $variant:ident, $t:ty) => {
        fn $name(&self, name: &str) -> Option<&[$t]> {
            match self.get(name)? {
                Property::$variant(v) => Some(v),
                _ => None,
            }
        }
    };
}

impl PropertyAccess for Row {
    fn new() -> Self {
        Self(Vec::with_capacity(12))
    }

    fn set_property(&mut self, name: &str, property: Property) {
        let key = name_hash(name);
        match self.0.iter_mut().find(|(k, _)| *k == key) {
            Some(slot) => slot.1 = property,
            None => self.0.push((key, property)),
        }
    }

    scalar!(get_char, Char, i8);
    scalar!(get_uchar, UChar, u8);
    scalar!(get_short, Short, i16);
    scalar!(get_ushort, UShort, u16);
    scalar!(get_int, Int, i32);
    scalar!(get_uint, UInt, u32);
    scalar!(get_float, Float, f32);
    scalar!(get_double, Double, f64);
    list!(get_list_char, ListChar, i8);
    list!(get_list_uchar, ListUChar, u8);
    list!(get_list_short, ListShort, i16);
    list!(get_list_ushort, ListUShort, u16);
    list!(get_list_int, ListInt, i32);
    list!(get_list_uint, ListUInt, u32);
    list!(get_list_float, ListFloat, f32);
    list!(get_list_double, ListDouble, f64);
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_row_gives_back_what_was_set_by_name_and_type() {
        let mut row = Row::new();
        row.set_property("x", Property::Float(1.5));
        row.set_property("vertex_indices", Property::ListInt(vec![0, 1, 2]));
        row.set_property("x", Property::Float(2.5));
        assert_eq!(row.get_float("x"), Some(2.5));
        assert_eq!(row.get_double("x"), None);
        assert_eq!(row.get_list_int("vertex_indices"), Some(&[0, 1, 2][..]));
        assert_eq!(row.get_float("y"), None);
        // FNV-1a's published test vector.
        assert_eq!(name_hash("a"), 0xaf63_dc4c_8601_ec8c);
    }
}
