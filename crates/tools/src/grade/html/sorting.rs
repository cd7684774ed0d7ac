//! The class table's row order. Without script the rows come by name as a
//! person reads a list of names (`by_name`), not by the folder names' bytes
//! that grades.csv keeps (which put `<img…>`, `Zoe` and `__MACOSX` before
//! `ada`). `SCRIPT`, the report's one script, inline, makes each heading a
//! link that sorts by that column (name, total, each scene's points; again:
//! the other way), through the URL's fragment (`#sort=total`,
//! `#sort=-scene-2`), so a sorted view can be bookmarked or sent, and a test
//! can open one.

use crate::grade::model::StudentGrades;

/// `students` by name: their letters and digits compared with case
/// ignored, then the whole name with case ignored, then as given (the
/// class's byte order). The script sorts as the browser's language does
/// (accents, numbers); this is its fallback.
pub(super) fn by_name(students: &[StudentGrades]) -> Vec<&StudentGrades> {
    let mut ordered: Vec<&StudentGrades> = students.iter().collect();
    ordered.sort_by_cached_key(|s| name_key(&s.student));
    ordered
}

fn name_key(name: &str) -> (String, String) {
    let lower = name.to_lowercase();
    let letters = lower.chars().filter(|c| c.is_alphanumeric()).collect();
    (letters, lower)
}

/// The row anchor of a student in index.html, which the histograms' lists
/// link to (slugs are `[a-z0-9_-]`: safe in an id and a fragment).
pub(super) fn row_anchor(student: &StudentGrades) -> String {
    format!("row-{}", student.slug)
}

/// Sorts `table.grades` by the column the fragment names: a heading's
/// `data-sort` key (`name`, `total`, `scene-N`), `-` before it for the
/// other way. Names compare by their letters and digits as `by_name` does,
/// but as the browser's language orders them (É with E, case and accents
/// aside, digits as numbers); points as numbers (a cell's
/// `data-points`), lowest first, so that who needs help comes first. Ties
/// go by name. No fragment, or one that names no column, is name order.
pub(super) const SCRIPT: &str = r##"(function () {
  "use strict";
  var table = document.querySelector("table.grades");
  if (!table || !table.tHead || !table.tBodies.length) return;
  var heads = Array.prototype.slice.call(table.tHead.rows[0].cells);
  var keys = heads.map(function (th) { return th.getAttribute("data-sort"); });
  var body = table.tBodies[0];
  var collator = new Intl.Collator(undefined, { sensitivity: "base", numeric: true });
  // Letters and digits first: `<img …>` and `__MACOSX` go under i and m.
  function names(a, b) {
    return collator.compare(a.letters, b.letters) || collator.compare(a.name, b.name);
  }
  var rows = Array.prototype.slice.call(body.rows).map(function (row, index) {
    var points = Array.prototype.map.call(row.cells, function (cell) {
      var value = parseFloat(cell.getAttribute("data-points"));
      return isNaN(value) ? -Infinity : value;
    });
    var name = (row.cells[0].querySelector("bdi") || row.cells[0]).textContent;
    var letters = name.replace(/[^\p{L}\p{N}]+/gu, "");
    return { row: row, index: index, name: name, letters: letters, points: points };
  });
  // Each sortable heading's first line (its label) becomes the link.
  var links = heads.map(function (th, column) {
    if (!keys[column] || !th.firstChild) return null;
    var link = document.createElement("a");
    link.className = "sort";
    th.insertBefore(link, th.firstChild);
    link.appendChild(link.nextSibling);
    return link;
  });
  function byName(a, b) { return names(a, b) || a.index - b.index; }
  function sort(fragment) {
    var asked = /^#sort=(-?)([a-z0-9-]+)$/.exec(fragment);
    var column = asked ? keys.indexOf(asked[2]) : -1;
    var descending = column >= 0 && asked[1] === "-";
    if (column < 0) column = keys.indexOf("name");
    var sorted = rows.slice().sort(function (a, b) {
      var by = keys[column] === "name" ? names(a, b) : a.points[column] - b.points[column];
      return (descending ? -by : by) || byName(a, b);
    });
    sorted.forEach(function (entry) { body.appendChild(entry.row); });
    heads.forEach(function (th, i) {
      if (!links[i]) return;
      var now = i === column;
      if (now) th.setAttribute("aria-sort", descending ? "descending" : "ascending");
      else th.removeAttribute("aria-sort");
      links[i].href = "#sort=" + (now && !descending ? "-" : "") + keys[i];
      links[i].title = "Sort by " + links[i].textContent + (now && !descending ? ", the other way" : "");
    });
  }
  window.addEventListener("hashchange", function () {
    if (location.hash.indexOf("#sort=") === 0) sort(location.hash);
  });
  sort(location.hash);
})();
"##;

#[cfg(test)]
mod tests {
    use super::*;
    use crate::grade::html::sample_class::{class, matched};

    #[test]
    fn names_come_by_their_letters_case_and_punctuation_aside() {
        // Byte order (the CSV's) is `<img…>` (0x3C), `Zoe` (Z is 0x5A),
        // `__MACOSX` (0x5F), `ada`, `bob`. By letters, lowercased: ada,
        // bob, imgsrcx…, macosx, zoe; `Bob` and `bob` tie on letters and
        // on the lowercased name, so they keep their byte order (B first).
        let class = class(&[
            ("<img src=x>", vec![matched()]),
            ("Bob", vec![matched()]),
            ("Zoe", vec![matched()]),
            ("__MACOSX", vec![matched()]),
            ("ada", vec![matched()]),
            ("bob", vec![matched()]),
        ]);
        let names: Vec<&str> = by_name(&class.students)
            .iter()
            .map(|s| s.student.as_str())
            .collect();
        assert_eq!(
            names,
            ["ada", "Bob", "bob", "<img src=x>", "__MACOSX", "Zoe"]
        );
    }
}
