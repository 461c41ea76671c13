//! `lumiere list`: the catalogue, topic by topic.

use anyhow::Result;
use lumiere::catalogue::{self, Topic};

/// List the catalogue by topic: id, year, title and what each entry shows.
#[derive(clap::Args, Debug)]
pub struct Args {
    /// One line per entry, without the summaries.
    #[arg(long)]
    brief: bool,
    /// Only this topic's entries.
    #[arg(long, value_parser = topic_name)]
    topic: Option<Topic>,
    /// Print every entry's [algorithm] table as JSON instead.
    #[arg(long, conflicts_with = "ids")]
    json: bool,
    /// Only the ids, one a line, for scripts (`for id in $(lumiere list --ids)`).
    #[arg(long, conflicts_with = "brief")]
    ids: bool,
}

/// A topic by its name, for `--topic`.
pub fn topic_name(name: &str) -> Result<Topic, String> {
    Topic::ALL
        .into_iter()
        .find(|t| t.name() == name)
        .ok_or_else(|| {
            let names: Vec<&str> = Topic::ALL.iter().map(|t| t.name()).collect();
            format!("the topics are {}", names.join(", "))
        })
}

pub fn run(args: Args) -> Result<()> {
    let entries: Vec<_> = catalogue::entries()?
        .into_iter()
        .filter(|e| args.topic.is_none_or(|t| e.algorithm.topic == t))
        .collect();
    if args.ids {
        for e in &entries {
            outln!("{}", e.algorithm.id)?;
        }
        return Ok(());
    }
    if args.json {
        let tables: Vec<_> = entries.iter().map(|e| &e.algorithm).collect();
        outln!("{}", serde_json::to_string_pretty(&tables)?)?;
        return Ok(());
    }
    let width = entries
        .iter()
        .map(|e| e.algorithm.id.len())
        .max()
        .unwrap_or(0);
    for topic in Topic::ALL {
        let of_topic: Vec<_> = entries
            .iter()
            .filter(|e| e.algorithm.topic == topic)
            .collect();
        if of_topic.is_empty() {
            continue;
        }
        outln!("{} [{}]\n", topic.title(), topic.name())?;
        for e in of_topic {
            let a = &e.algorithm;
            outln!("{:width$}  {}  {}", a.id, a.year, a.title)?;
            if !args.brief {
                for line in wrap(&a.summary, 84) {
                    outln!("    {line}")?;
                }
                outln!()?;
            }
        }
        if args.brief {
            outln!()?;
        }
    }
    Ok(())
}

/// `text`'s words in lines of at most `width` characters (a longer word alone).
pub fn wrap(text: &str, width: usize) -> Vec<String> {
    let mut lines = Vec::new();
    let mut line = String::new();
    for word in text.split_whitespace() {
        if !line.is_empty() && line.chars().count() + 1 + word.chars().count() > width {
            lines.push(std::mem::take(&mut line));
        }
        if !line.is_empty() {
            line.push(' ');
        }
        line.push_str(word);
    }
    if !line.is_empty() {
        lines.push(line);
    }
    lines
}
