//! What a batch works on: the parts of a folder or a manifest, each with its `midsurf run` options, and the
//! shard of them this process takes.

use std::collections::{BTreeMap, HashMap};
use std::path::{Path, PathBuf};

use crate::error::Error;

/// The `midsurf run` options a manifest may set per part, by flag name (a column or key may also spell them
/// with underscores). They are passed to `midsurf run` as they are, so a part gets exactly the run it would
/// get by hand.
pub const OPTIONS: [&str; 8] =
    ["t-max", "draft-max", "fillet-max", "hole-max", "boss-max", "keep-holes", "position", "t-bands"];

/// Options of one part: flag name (one of `OPTIONS`) to value; `keep-holes` is "true" or "false".
pub type Options = BTreeMap<String, String>;

/// One part of a batch.
#[derive(Debug, Clone, PartialEq)]
pub struct Part {
    /// Unique within the batch; names the outputs (`NAME.step`, `NAME.json`, `NAME.log`).
    pub name: String,
    pub input: PathBuf,
    pub options: Options,
}

impl Part {
    /// The options as `midsurf run` arguments, in a fixed order (that of `OPTIONS`), so that the resume key
    /// of a part does not depend on how its manifest spelled them.
    pub fn run_args(&self) -> Vec<String> {
        let mut args = Vec::new();
        for flag in OPTIONS {
            match (flag, self.options.get(flag)) {
                (_, None) => {}
                ("keep-holes", Some(v)) => {
                    if v == "true" {
                        args.push("--keep-holes".to_string());
                    }
                }
                (_, Some(v)) => args.push(format!("--{flag}={v}")),
            }
        }
        args
    }
}

/// Which share of the parts this process takes: the `index`-th (1-based) of `count`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Shard {
    pub index: usize,
    pub count: usize,
}

impl Shard {
    /// `I/N` with 1 <= I <= N (a job array's task id, e.g. Slurm's `--array=1-N`).
    pub fn parse(s: &str) -> Result<Shard, String> {
        let bad = || format!("'{s}' is not a shard I/N with 1 <= I <= N (e.g. 3/8)");
        let (i, n) = s.split_once('/').ok_or_else(bad)?;
        let (index, count) =
            (i.trim().parse::<usize>().map_err(|_| bad())?, n.trim().parse::<usize>().map_err(|_| bad())?);
        if index == 0 || index > count {
            return Err(bad());
        }
        Ok(Shard { index, count })
    }

    /// The parts of this shard. Parts are sorted by name and dealt out in turn (part k, 0-based, to shard
    /// k mod N + 1): every part lands in exactly one shard whatever N, and since a folder sorted by name tends
    /// to group similar parts, dealing spreads them (and their run times) over the shards better than blocks.
    pub fn select(self, parts: Vec<Part>) -> Vec<Part> {
        parts.into_iter().enumerate().filter(|(k, _)| k % self.count + 1 == self.index).map(|(_, p)| p).collect()
    }
}

/// The parts of a folder (its `*.step`/`*.stp` files, not recursing) or of a manifest (`.csv` or `.json`),
/// sorted by name, each with the batch's options overridden by its own.
/// Checks the `midsurf run` arguments of a part (after `run PART -o OUT`), with the message `run` would give;
/// the CLI hands in its own parser, so the batch never depends on the CLI.
pub type RunArgsCheck = fn(Vec<String>) -> Result<(), String>;

pub fn parts(source: &Path, defaults: &Options, check: RunArgsCheck) -> Result<Vec<Part>, Error> {
    let mut parts = if source.is_dir() {
        folder(source, defaults)?
    } else {
        let text = std::fs::read_to_string(source).map_err(|e| match e.kind() {
            std::io::ErrorKind::NotFound => Error::input(source, "no such file or folder"),
            _ => Error::input(source, format!("cannot read: {e}")),
        })?;
        let base = source.parent().unwrap_or(Path::new("")).to_path_buf();
        let rows = match extension(source).as_str() {
            "csv" => csv_rows(&text).map_err(|e| Error::input(source, e))?,
            "json" => json_rows(&text).map_err(|e| Error::input(source, e))?,
            _ => return Err(Error::input(source, "is neither a folder nor a manifest (.csv or .json)")),
        };
        let mut parts = Vec::new();
        for row in rows {
            let line = row.0.clone();
            parts.push(
                manifest_part(&base, defaults, row, check).map_err(|e| Error::input(source, format!("{line}: {e}")))?,
            );
        }
        parts
    };
    parts.sort_by(|a, b| a.name.cmp(&b.name));
    let mut seen: HashMap<&str, &Path> = HashMap::new();
    for p in &parts {
        if let Some(first) = seen.insert(&p.name, &p.input) {
            let why = format!(
                "two parts are named '{}' ({} and {}); give one a name",
                p.name,
                first.display(),
                p.input.display()
            );
            return Err(Error::input(source, why));
        }
    }
    if parts.is_empty() {
        return Err(Error::input(source, "holds no part (no .step or .stp file)"));
    }
    Ok(parts)
}

fn extension(path: &Path) -> String {
    path.extension().map(|e| e.to_string_lossy().to_lowercase()).unwrap_or_default()
}

fn folder(dir: &Path, defaults: &Options) -> Result<Vec<Part>, Error> {
    let entries = std::fs::read_dir(dir).map_err(|e| Error::input(dir, format!("cannot list: {e}")))?;
    let mut parts = Vec::new();
    for entry in entries {
        let path = entry.map_err(|e| Error::input(dir, format!("cannot list: {e}")))?.path();
        if path.is_file() && matches!(extension(&path).as_str(), "step" | "stp") {
            let name = stem(&path);
            check_name(&name).map_err(|e| Error::input(&path, e))?;
            parts.push(Part { name, input: path, options: defaults.clone() });
        }
    }
    Ok(parts)
}

fn stem(path: &Path) -> String {
    path.file_stem().map(|s| s.to_string_lossy().into_owned()).unwrap_or_default()
}

/// The prefix of the batch's own files in the output folder, which no part may take as its name.
pub const SUMMARY_PREFIX: &str = "batch-summary";

fn check_name(name: &str) -> Result<(), String> {
    if name.is_empty() || name.starts_with('.') || name.contains(['/', '\\']) {
        return Err(format!("'{name}' cannot name output files (empty, hidden, or holds a path separator)"));
    }
    if name.starts_with(SUMMARY_PREFIX) {
        return Err(format!("'{name}' would clash with the batch's own {SUMMARY_PREFIX}.* files; rename it"));
    }
    Ok(())
}

/// A manifest row: where it came from ("line 3", "part 2") and its fields as text, by column or key.
type Row = (String, Vec<(String, String)>);

fn manifest_part(base: &Path, defaults: &Options, (_, fields): Row, check: RunArgsCheck) -> Result<Part, String> {
    let mut input = None;
    let mut name = None;
    let mut options = defaults.clone();
    for (key, value) in fields {
        let key = key.trim().to_lowercase().replace('_', "-");
        let value = value.trim().to_string();
        match key.as_str() {
            "input" | "part" | "file" => input = Some(value),
            "name" => name = Some(value),
            flag if OPTIONS.contains(&flag) => {
                if value.is_empty() {
                    continue; // an empty cell keeps the batch's option
                }
                let value = if flag == "keep-holes" { boolean(&value)? } else { value };
                options.insert(flag.to_string(), value);
            }
            other => {
                return Err(format!("unknown column or key '{other}' (known: input, name, {})", OPTIONS.join(", ")))
            }
        }
    }
    let input = input.filter(|s| !s.is_empty()).ok_or("no input (a column or key 'input' naming the STEP file)")?;
    let path = base.join(&input);
    let name = name.filter(|s| !s.is_empty()).unwrap_or_else(|| stem(&path));
    check_name(&name)?;
    let part = Part { name, input: path, options };
    validate(&part, check)?;
    Ok(part)
}

fn boolean(value: &str) -> Result<String, String> {
    match value.to_lowercase().as_str() {
        "true" | "yes" | "1" => Ok("true".into()),
        "false" | "no" | "0" => Ok("false".into()),
        _ => Err(format!("keep-holes '{value}' is not true or false")),
    }
}

/// Checks a part's options with `midsurf run`'s own parser, so a bad value fails the batch before any part
/// runs, with the message `midsurf run` would give.
fn validate(part: &Part, check: RunArgsCheck) -> Result<(), String> {
    check(part.run_args()).map_err(|first| format!("part '{}': {first}", part.name))
}

/// CSV rows (a header first; fields may be double-quoted, with "" for a quote inside), blank lines skipped.
fn csv_rows(text: &str) -> Result<Vec<Row>, String> {
    let mut lines = text.lines().enumerate().filter(|(_, l)| !l.trim().is_empty());
    let (_, header) = lines.next().ok_or("is empty (a CSV manifest needs a header row, e.g. input,t_max)")?;
    let header = csv_fields(header).map_err(|e| format!("line 1: {e}"))?;
    let mut rows = Vec::new();
    for (i, line) in lines {
        let fields = csv_fields(line).map_err(|e| format!("line {}: {e}", i + 1))?;
        if fields.len() > header.len() {
            return Err(format!("line {}: {} fields for {} columns", i + 1, fields.len(), header.len()));
        }
        rows.push((format!("line {}", i + 1), header.iter().cloned().zip(fields).collect()));
    }
    Ok(rows)
}

fn csv_fields(line: &str) -> Result<Vec<String>, String> {
    let mut fields = vec![String::new()];
    let mut chars = line.chars().peekable();
    let mut quoted = false;
    while let Some(c) = chars.next() {
        let field = fields.last_mut().expect("never empty");
        match (quoted, c) {
            (true, '"') if chars.peek() == Some(&'"') => {
                chars.next();
                field.push('"');
            }
            (true, '"') => quoted = false,
            (true, c) => field.push(c),
            (false, '"') if field.trim().is_empty() => {
                field.clear();
                quoted = true;
            }
            (false, ',') => fields.push(String::new()),
            (false, c) => field.push(c),
        }
    }
    if quoted {
        return Err("a quoted field is not closed".into());
    }
    Ok(fields)
}

/// JSON: an array of objects, or an object whose `parts` is one; values are strings, numbers or booleans.
fn json_rows(text: &str) -> Result<Vec<Row>, String> {
    let value: serde_json::Value = serde_json::from_str(text).map_err(|e| format!("is not valid JSON: {e}"))?;
    let list = match &value {
        serde_json::Value::Array(list) => list,
        serde_json::Value::Object(map) => match map.get("parts") {
            Some(serde_json::Value::Array(list)) => list,
            _ => return Err("a JSON manifest is an array of parts, or an object with an array 'parts'".into()),
        },
        _ => return Err("a JSON manifest is an array of parts, or an object with an array 'parts'".into()),
    };
    let mut rows = Vec::new();
    for (i, item) in list.iter().enumerate() {
        let at = format!("part {}", i + 1);
        let fields = match item {
            serde_json::Value::String(input) => vec![("input".to_string(), input.clone())],
            serde_json::Value::Object(map) => {
                let mut fields = Vec::new();
                for (k, v) in map {
                    let text = match v {
                        serde_json::Value::String(s) => s.clone(),
                        serde_json::Value::Number(n) => n.to_string(),
                        serde_json::Value::Bool(b) => b.to_string(),
                        serde_json::Value::Null => String::new(),
                        _ => return Err(format!("{at}: '{k}' is neither a string, a number nor a boolean")),
                    };
                    fields.push((k.clone(), text));
                }
                fields
            }
            _ => return Err(format!("{at}: is neither a file name nor an object")),
        };
        rows.push((at, fields));
    }
    Ok(rows)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn named(names: &[&str]) -> Vec<Part> {
        names.iter().map(|n| Part { name: n.to_string(), input: PathBuf::from(n), options: Options::new() }).collect()
    }

    #[test]
    fn shards_partition_the_parts_exactly() {
        let names: Vec<String> = (0..23).map(|i| format!("p{i:02}")).collect();
        let all = named(&names.iter().map(String::as_str).collect::<Vec<_>>());
        for count in 1..=7 {
            let mut seen: Vec<String> = Vec::new();
            for index in 1..=count {
                let shard = Shard::parse(&format!("{index}/{count}")).unwrap();
                let taken = shard.select(all.clone());
                // Balanced: sizes differ by one at most.
                assert!(taken.len() >= 23 / count && taken.len() <= 23 / count + 1, "{index}/{count}");
                seen.extend(taken.into_iter().map(|p| p.name));
            }
            seen.sort();
            assert_eq!(seen, names, "shards of {count} overlap or leave a gap");
        }
    }

    #[test]
    fn shard_syntax() {
        assert_eq!(Shard::parse("2/5"), Ok(Shard { index: 2, count: 5 }));
        for bad in ["0/5", "6/5", "1", "a/b", "1/0", ""] {
            assert!(Shard::parse(bad).is_err(), "{bad}");
        }
    }

    #[test]
    fn csv_quotes_and_options() {
        let rows = csv_rows("input,t_max,keep_holes\n\"a, b.step\",2.5,yes\n\nc.step,,\n").unwrap();
        let parts: Vec<Part> =
            rows.into_iter().map(|r| manifest_part(Path::new("m"), &Options::new(), r, accept).unwrap()).collect();
        assert_eq!(parts[0].input, PathBuf::from("m/a, b.step"));
        assert_eq!(parts[0].name, "a, b");
        assert_eq!(parts[0].run_args(), ["--t-max=2.5", "--keep-holes"]);
        assert!(parts[1].run_args().is_empty());
    }

    /// Accepts every argument (the CLI's own check is tested beside it).
    fn accept(_: Vec<String>) -> Result<(), String> {
        Ok(())
    }

    /// Refuses a negative t_max, as `run`'s parser does.
    fn no_negative_t_max(args: Vec<String>) -> Result<(), String> {
        match args.iter().find(|a| a.starts_with("--t-max=-")) {
            Some(a) => Err(format!("invalid value '{a}': not a positive length")),
            None => Ok(()),
        }
    }

    #[test]
    fn manifest_errors_name_the_row_and_the_problem() {
        let bad = |text: &str| {
            let rows = csv_rows(text).unwrap();
            let part = |r| manifest_part(Path::new(""), &Options::new(), r, no_negative_t_max);
            rows.into_iter().map(part).collect::<Result<Vec<_>, _>>()
        };
        let negative = bad("input,t_max\na.step,-1\n").unwrap_err();
        assert!(negative.contains("part 'a'") && negative.contains("not a positive length"), "{negative}");
        assert!(bad("input,colour\na.step,red\n").unwrap_err().contains("unknown column"));
        assert!(bad("name\nx\n").unwrap_err().contains("no input"));
    }

    #[test]
    fn json_manifest_forms() {
        let rows = json_rows(r#"{"parts": ["a.step", {"input": "b.stp", "name": "bee", "hole_max": 3}]}"#).unwrap();
        let parts: Vec<Part> =
            rows.into_iter().map(|r| manifest_part(Path::new(""), &Options::new(), r, accept).unwrap()).collect();
        assert_eq!(parts[0].name, "a");
        assert_eq!((parts[1].name.as_str(), parts[1].run_args()), ("bee", vec!["--hole-max=3".to_string()]));
        assert!(json_rows("[[1]]").is_err());
    }
}
