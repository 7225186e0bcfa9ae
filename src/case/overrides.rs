//! `--set KEY=VALUE`: overrides applied to the parsed TOML table before validation.
//!
//! `KEY` is a dotted path (`time.t_end`, `scene.phases.1.velocity` for array items, which may
//! also be written as the messages name them, `scene.phases[1].velocity`); `VALUE` is a TOML
//! value (`50`, `1e-3`, `"eq4"`, `[1, 2]`); a bare word that is not TOML is taken
//! as a string, so `friction.rstar_law=eq4` works too.

use crate::case::error::CaseError;

/// Applies one `KEY=VALUE` override to `table`.
pub fn apply(table: &mut toml::Table, item: &str) -> Result<(), CaseError> {
    let Some((key, raw)) = item.split_once('=') else {
        return Err(CaseError::Override(format!("--set {item}: expected KEY=VALUE, e.g. --set time.t_end=50")));
    };
    let (typed, key) = (key.trim(), &dotted(key.trim()));
    let raw = raw.trim();
    if key.is_empty() || key.split('.').any(str::is_empty) {
        return Err(CaseError::Override(format!("--set {item}: the key must be a dotted path such as time.t_end")));
    }
    if raw.is_empty() {
        return Err(CaseError::Override(format!("--set {item}: the value is empty")));
    }
    let value = parse_value(raw);
    let parts: Vec<&str> = key.split('.').collect();
    let (last, parents) = parts.split_last().expect("non-empty key");
    let mut current = toml::Value::Table(std::mem::take(table));
    let result = set(&mut current, parents, last, value, typed);
    if let toml::Value::Table(t) = current {
        *table = t;
    }
    result
}

/// `key` with each array index written `name[i]`, as messages name keys, turned into `name.i`.
fn dotted(key: &str) -> String {
    let mut out = String::with_capacity(key.len());
    let mut rest = key;
    while let Some(open) = rest.find('[') {
        let Some(close) = rest[open..].find(']').map(|c| open + c) else { break };
        let index = &rest[open + 1..close];
        if index.is_empty() || !index.bytes().all(|b| b.is_ascii_digit()) {
            break;
        }
        out.push_str(&rest[..open]);
        out.push('.');
        out.push_str(index);
        rest = &rest[close + 1..];
    }
    out.push_str(rest);
    out
}

fn parse_value(raw: &str) -> toml::Value {
    match format!("v = {raw}").parse::<toml::Table>() {
        Ok(mut t) => t.remove("v").expect("parsed key"),
        Err(_) => toml::Value::String(raw.to_string()),
    }
}

fn set(node: &mut toml::Value, parents: &[&str], last: &str, value: toml::Value, key: &str) -> Result<(), CaseError> {
    let mut node = node;
    // Walk the parents, creating tables where the case leaves them out.
    let mut path = String::new();
    for part in parents {
        if !path.is_empty() {
            path.push('.');
        }
        path.push_str(part);
        node = match node {
            toml::Value::Table(t) => {
                t.entry(part.to_string()).or_insert_with(|| toml::Value::Table(toml::Table::new()))
            }
            toml::Value::Array(items) => {
                let index = array_index(part, items.len(), &path, key)?;
                &mut items[index]
            }
            _ => return Err(not_a_table(&path, key)),
        };
    }
    match node {
        toml::Value::Table(t) => {
            t.insert(last.to_string(), value);
            Ok(())
        }
        toml::Value::Array(items) => {
            let index = array_index(last, items.len(), key, key)?;
            items[index] = value;
            Ok(())
        }
        _ => Err(not_a_table(&parents.join("."), key)),
    }
}

fn array_index(part: &str, len: usize, path: &str, key: &str) -> Result<usize, CaseError> {
    match part.parse::<usize>() {
        Ok(i) if i < len => Ok(i),
        _ => Err(CaseError::Override(format!(
            "--set {key}: {path} must index an existing item of the array (0 to {})",
            len.saturating_sub(1)
        ))),
    }
}

fn not_a_table(path: &str, key: &str) -> CaseError {
    CaseError::Override(format!("--set {key}: {path} is a value, not a table, so it has no keys"))
}
