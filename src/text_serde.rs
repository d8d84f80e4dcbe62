//! Serde for the types written as text (a tile `SL`, a fold word `SLLS`, a shard `2/8`):
//! serialized through `Display` and read back through `FromStr`, so that JSON holds the
//! same text the tools print and read.

/// Implements `serde::Serialize` (through `Display`) and `serde::Deserialize` (from a
/// string, through `FromStr`; its error's message on failure) for each type named.
macro_rules! serde_as_text {
    ($($t:ty),+ $(,)?) => {$(
        impl serde::Serialize for $t {
            fn serialize<S: serde::Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
                s.collect_str(self)
            }
        }

        impl<'de> serde::Deserialize<'de> for $t {
            fn deserialize<D: serde::Deserializer<'de>>(d: D) -> Result<$t, D::Error> {
                let text = <String as serde::Deserialize>::deserialize(d)?;
                text.parse().map_err(serde::de::Error::custom)
            }
        }
    )+};
}

pub(crate) use serde_as_text;
