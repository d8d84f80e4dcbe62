//! Adding up the reports of a sharded count (`fold-enum --shard K/M --json`, one per part),
//! refusing a set that misses a part, holds one twice or mixes different searches.
//!
//! The parts of a search are disjoint and together cover it (`--shard K/M` takes every
//! `M`-th word at the cut depth, starting at the `K`-th; lengths up to the cut are counted by
//! part 1 alone), so the merged valid counts are the sums of the parts', exactly.

use std::fmt;
use std::str::FromStr;

use super::{CountError, CountOptions, CountRow};

/// Part `k` (1-based) of `m` disjoint parts of a search. Written `K/M` (in JSON too).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct Shard {
    /// The part, `1..=m`.
    pub k: usize,
    /// The number of parts.
    pub m: usize,
}

impl Shard {
    /// Part `k` of `m`, checked: `1 <= k <= m`.
    pub fn new(k: usize, m: usize) -> Result<Shard, CountError> {
        if k < 1 || k > m {
            return Err(CountError::BadShard { k, m });
        }
        Ok(Shard { k, m })
    }
}

impl fmt::Display for Shard {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}/{}", self.k, self.m)
    }
}

impl FromStr for Shard {
    type Err = CountError;

    /// `K/M`, for example `2/8`.
    fn from_str(s: &str) -> Result<Shard, CountError> {
        let bad = || CountError::ShardText {
            text: s.to_string(),
        };
        let (k, m) = s.split_once('/').ok_or_else(bad)?;
        let k = k.trim().parse().map_err(|_| bad())?;
        let m = m.trim().parse().map_err(|_| bad())?;
        Shard::new(k, m).map_err(|_| bad())
    }
}

crate::text_serde::serde_as_text!(Shard);

/// What `fold-enum --json` prints: the rows, the wall time, and for a shard which part it is
/// and the options of its search (so that parts of different searches are not added).
#[derive(Clone, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct CountReport {
    /// One row per chain length.
    pub rows: Vec<CountRow>,
    /// Wall time in seconds (for a merged report: the sum over its parts).
    #[serde(default)]
    pub seconds: f64,
    /// The part of the search, `None` for a whole search.
    #[serde(default)]
    pub shard: Option<Shard>,
    /// The options of the search (shards carry them).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub options: Option<CountOptions>,
}

impl CountReport {
    /// Adds up the reports of all the parts of one sharded search, given as `(file name,
    /// JSON text)`: the valid counts are summed, the time too. Refuses a report that is not a
    /// shard, a part given twice or missing, parts of different searches, and random-chain
    /// probabilities (they are not counts: run `--random` unsharded).
    pub fn merge(files: &[(String, String)]) -> Result<CountReport, CountError> {
        merge_reports(files)
    }

    /// Reads a report from JSON text.
    pub fn from_json(text: &str) -> Result<CountReport, serde_json::Error> {
        serde_json::from_str(text)
    }
}

pub(super) fn list(parts: &[usize]) -> String {
    let v: Vec<String> = parts.iter().map(|k| k.to_string()).collect();
    v.join(", ")
}

/// The same search: options (all but the shard) and the rows' lengths and totals.
fn same_search(a: &CountReport, b: &CountReport) -> Result<(), String> {
    let strip = |o: &Option<CountOptions>| o.map(|o| CountOptions { shard: None, ..o });
    if strip(&a.options) != strip(&b.options) {
        return Err("options".into());
    }
    let shape = |r: &CountReport| -> Vec<(usize, u128, u128)> {
        r.rows
            .iter()
            .map(|row| (row.tiles, row.candidates, row.searched))
            .collect()
    };
    if shape(a) != shape(b) {
        return Err("rows (lengths or word totals)".into());
    }
    Ok(())
}

/// Adds up the reports of all the parts of one sharded search, given as `(file name, JSON
/// text)`: the valid counts are summed, the time too. Refuses a report that is not a shard, a
/// part given twice or missing, parts of different searches, and random-chain probabilities
/// (they are not counts: run `--random` unsharded).
pub(crate) fn merge_reports(files: &[(String, String)]) -> Result<CountReport, CountError> {
    let mut parts: Vec<(&str, Shard, CountReport)> = Vec::with_capacity(files.len());
    for (file, text) in files {
        let report = CountReport::from_json(text).map_err(|e| CountError::Json {
            file: file.clone(),
            message: e.to_string(),
        })?;
        let Some(shard) = report.shard else {
            return Err(CountError::NotAShard { file: file.clone() });
        };
        if report.rows.iter().any(|r| r.p_random.is_some()) {
            return Err(CountError::Mismatch {
                file: file.clone(),
                first: file.clone(),
                what: "random-chain probabilities (not counts: they do not add up)".into(),
            });
        }
        parts.push((file, shard, report));
    }
    let Some((first, first_shard, base)) = parts.first() else {
        return Err(CountError::NoReports);
    };
    let m = first_shard.m;
    let mut seen: Vec<Option<&str>> = vec![None; m + 1];
    let mut merged = CountReport {
        rows: base.rows.clone(),
        seconds: 0.0,
        shard: None,
        options: base.options.map(|o| CountOptions { shard: None, ..o }),
    };
    for row in &mut merged.rows {
        row.valid = 0;
    }
    for (file, shard, report) in &parts {
        if shard.m != m {
            return Err(CountError::PartsDisagree {
                file: file.to_string(),
                shard: *shard,
                first: first.to_string(),
                expected: m,
            });
        }
        if let Some(before) = seen[shard.k] {
            return Err(CountError::Doubled {
                shard: *shard,
                first: before.to_string(),
                second: file.to_string(),
            });
        }
        seen[shard.k] = Some(file);
        same_search(base, report).map_err(|what| CountError::Mismatch {
            file: file.to_string(),
            first: first.to_string(),
            what,
        })?;
        for (sum, row) in merged.rows.iter_mut().zip(&report.rows) {
            sum.valid += row.valid;
        }
        merged.seconds += report.seconds;
    }
    let missing: Vec<usize> = (1..=m).filter(|&k| seen[k].is_none()).collect();
    if !missing.is_empty() {
        return Err(CountError::Missing { missing, m });
    }
    Ok(merged)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn report(opts: &CountOptions) -> String {
        let rows = opts.count_valid(&|_, _| {}).unwrap();
        let shard = opts.shard.map(|(k, m)| Shard::new(k, m).unwrap());
        let r = CountReport {
            rows,
            seconds: 0.5,
            shard,
            options: Some(*opts),
        };
        serde_json::to_string(&r).unwrap()
    }

    fn parts(opts: CountOptions, ks: &[usize], m: usize) -> Vec<(String, String)> {
        ks.iter()
            .map(|&k| (format!("part-{k}.json"), report(&opts.with_shard(k, m))))
            .collect()
    }

    #[test]
    fn parts_add_up_to_the_whole() {
        let opts = CountOptions::default().with_tiles(2, 13);
        let whole = opts.count_valid(&|_, _| {}).unwrap();
        // given in any order
        let merged = merge_reports(&parts(opts, &[3, 1, 4, 2], 4)).unwrap();
        assert_eq!(merged.rows, whole);
        assert_eq!(merged.shard, None);
        assert!((merged.seconds - 2.0).abs() < 1e-12);
        assert_eq!(merged.options, Some(opts));
    }

    #[test]
    fn missing_and_doubled_parts_are_refused() {
        let opts = CountOptions::default().with_tiles(2, 11);
        let e = merge_reports(&parts(opts, &[1, 3], 4)).unwrap_err();
        assert_eq!(
            e,
            CountError::Missing {
                missing: vec![2, 4],
                m: 4
            }
        );
        assert_eq!(e.to_string(), "shards missing: 2, 4 (of 4 parts)");
        let e = merge_reports(&parts(opts, &[1, 2, 2, 3], 3)).unwrap_err();
        assert!(
            matches!(&e, CountError::Doubled { shard, first, second }
                if shard.k == 2 && first == "part-2.json" && second == "part-2.json"),
            "{e}"
        );
        let mut mixed = parts(opts, &[1], 2);
        mixed.extend(parts(opts, &[2], 3));
        assert!(matches!(
            merge_reports(&mixed).unwrap_err(),
            CountError::PartsDisagree { expected: 2, .. }
        ));
        assert_eq!(merge_reports(&[]).unwrap_err(), CountError::NoReports);
    }

    #[test]
    fn other_searches_and_non_shards_are_refused() {
        let opts = CountOptions::default().with_tiles(2, 11);
        let mut mixed = parts(opts, &[1], 2);
        mixed.extend(parts(opts.with_allow_opposite(true), &[2], 2));
        let e = merge_reports(&mixed).unwrap_err();
        assert!(
            matches!(&e, CountError::Mismatch { what, .. } if what == "options"),
            "{e}"
        );
        let mut longer = parts(opts, &[1], 2);
        longer.extend(parts(opts.with_tiles(2, 12), &[2], 2));
        assert!(matches!(
            merge_reports(&longer).unwrap_err(),
            CountError::Mismatch { .. }
        ));
        let whole = vec![("whole.json".to_string(), report(&opts))];
        assert_eq!(
            merge_reports(&whole).unwrap_err(),
            CountError::NotAShard {
                file: "whole.json".into()
            }
        );
        let bad = vec![("bad.json".to_string(), "{\"rows\": 3}".to_string())];
        assert!(
            matches!(merge_reports(&bad).unwrap_err(), CountError::Json { file, .. } if file == "bad.json")
        );
    }

    #[test]
    fn shards_read_and_write_as_k_of_m() {
        let s: Shard = "2/8".parse().unwrap();
        assert_eq!((s.k, s.m), (2, 8));
        assert_eq!(s.to_string(), "2/8");
        assert_eq!(" 3 / 4".parse::<Shard>().unwrap(), Shard { k: 3, m: 4 });
        for bad in ["0/3", "4/3", "2", "a/b", "-1/2", ""] {
            assert!(bad.parse::<Shard>().is_err(), "{bad}");
        }
        assert_eq!(serde_json::to_string(&s).unwrap(), "\"2/8\"");
        // the report of a whole search, as fold-enum prints it today, reads back
        let r = CountReport::from_json(r#"{"rows":[],"seconds":0.1,"shard":null}"#).unwrap();
        assert_eq!((r.shard, r.options), (None, None));
    }
}
