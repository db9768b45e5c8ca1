"""Class lists in, gradebook files out: the CSV side of `tools/grade --batch` (docs/grading.md, "Batch
grading"). What goes in the gradebooks' files follows what their importers do with a row (Moodle's
grade/import/csv/classes/load_data.php, Canvas's app/models/gradebook_importer.rb), as that section says."""
from __future__ import annotations

import csv
import io
import re
import unicodedata
from collections import defaultdict
from dataclasses import dataclass, field
from pathlib import Path


class RosterError(Exception):
    """The roster cannot be used as it is (tools/grade exits 2 before grading)."""


def normal(header: str) -> str:
    """A header as compared: lower case, accents, spaces and punctuation dropped ("Apellido(s)" -> apellidos)."""
    text = unicodedata.normalize("NFKD", header.strip().lower())
    return re.sub(r"[^0-9a-z]", "", "".join(c for c in text if not unicodedata.combining(c)))


# What a roster column holds, by its normalised header (English and Spanish; Moodle's and Canvas's exports).
ROLES: dict[str, set[str]] = {
    "email": {"email", "emailaddress", "mail", "correo", "correoelectronico", "direcciondecorreo",
              "direcciondecorreoelectronico"},
    "username": {"sisloginid", "loginid", "username", "user", "login", "userid", "usuario", "nombredeusuario"},
    "idnumber": {"sisuserid", "idnumber", "studentid", "studentnumber", "identifier", "matricula", "dni",
                 "numerodeid", "niu", "nia"},
    "id": {"id"},  # Canvas's user number in a Canvas export; a student number in any other roster
    "first": {"firstname", "givenname", "nombre"},
    "last": {"lastname", "surname", "familyname", "apellidos", "apellido"},
    "full": {"fullname", "name", "student", "studentname", "nombrecompleto", "alumno", "estudiante"},
    "section": {"section", "group", "grupo", "seccion"},
}
KEY_ROLES = ("email", "username", "idnumber", "id")  # a submission's folder name is matched against these
MOODLE_HEADERS = {"email": "Email address", "username": "Username", "idnumber": "ID number"}


def _delimiter(text: str) -> str:
    """Comma, semicolon or tab: the one that splits the header into the most fields (a header holds
    none of the others); on a tie, one no row has more fields than the header with."""
    def key(delimiter: str) -> tuple[int, bool]:
        try:
            rows = [r for r in csv.reader(io.StringIO(text, newline=""), delimiter=delimiter) if r]
        except csv.Error:
            return 0, False
        return (len(rows[0]), all(len(r) <= len(rows[0]) for r in rows)) if rows else (0, False)

    return max((",", ";", "\t"), key=key)


def read_csv(path: Path, option: str) -> list[tuple[int, list[str]]]:
    """(line number where the record starts, fields) of every non-empty record of ``path``."""
    try:
        raw = path.read_bytes()
    except OSError as error:
        raise RosterError(f"{option} {path}: cannot be read: {error.strerror or error}") from None
    try:
        text = raw.decode("utf-8-sig")
    except UnicodeDecodeError as error:
        line = raw[:error.start].count(b"\n") + 1
        raise RosterError(f"{option} {path}: line {line} is not UTF-8 text: save the file as \"CSV UTF-8\"") from None
    reader = csv.reader(io.StringIO(text, newline=""), delimiter=_delimiter(text), strict=True)
    records, start = [], 1
    try:
        for fields in reader:
            if any(f.strip() for f in fields):
                records.append((start, fields))
            start = reader.line_num + 1
    except csv.Error as error:
        raise RosterError(f"{option} {path}: line {start}: {error} (a quote opens a field that must end with "
                          "one; a quote inside a field is written twice)") from None
    return records


def csv_text(rows: list[list[str]]) -> str:
    """RFC 4180 text with a UTF-8 BOM: quotes where needed, inner quotes doubled, CRLF line ends."""
    buffer = io.StringIO(newline="")
    csv.writer(buffer, lineterminator="\r\n").writerows(rows)
    return "\ufeff" + buffer.getvalue()


@dataclass
class Roster:
    path: Path
    headers: list[str]
    rows: list[dict[str, str]]
    lines: list[int]  # the line of the file each row starts on
    columns: dict[str, list[str]] = field(default_factory=dict)  # role -> its headers, in file order

    @property
    def keys(self) -> list[str]:
        return [h for h in self.headers if any(h in self.columns.get(r, []) for r in KEY_ROLES)]

    @property
    def from_canvas(self) -> bool:
        """A Canvas export (its SIS columns): its ``ID`` is Canvas's own user number."""
        return any(normal(h) in ("sisuserid", "sisloginid") for h in self.headers)

    def value(self, row: dict[str, str], role: str) -> str:
        """The first filled column of ``role`` in ``row`` ("" if none)."""
        extra = self.columns.get("id", []) if role == "idnumber" and not self.from_canvas else []
        return next((row[h] for h in self.columns.get(role, []) + extra if row.get(h)), "")

    def names(self, row: dict[str, str]) -> tuple[str, str]:
        """(full name as "First Last", sortable name as "Last, First"), from whichever name columns exist."""
        first, last, full = self.value(row, "first"), self.value(row, "last"), self.value(row, "full")
        if first and last:
            return f"{first} {last}", f"{last}, {first}"
        full = full or first or last  # a lone "Nombre" is the whole name
        if full.count(",") == 1:  # Canvas's "Last, First"
            last, first = (p.strip() for p in full.split(","))
            return f"{first} {last}".strip(), full
        return full, full

    def match(self, submissions: list) -> tuple[dict[int, object], list]:
        """Row index -> its submission (anything with ``.ident``), and the submissions no row matches: a folder
        name is compared, ignoring case, with each id, user name and e-mail (whole or up to the @). Refused
        (RosterError): a name that matches two rows, two submissions that match one row (a grade lost)."""
        by_value: dict[str, set[int]] = defaultdict(set)
        for index, row in enumerate(self.rows):
            for key in self.keys:
                if value := row.get(key, "").strip().casefold():
                    by_value[value].add(index)
                    if key in self.columns.get("email", []) and "@" in value:
                        by_value[value.split("@", 1)[0]].add(index)
        matched: dict[int, object] = {}
        unmatched, problems = [], []
        for submission in submissions:
            rows = sorted(by_value.get(submission.ident.strip().casefold(), set()))
            if len(rows) > 1:
                problems.append(f"the submission {submission.ident} matches the rows on lines "
                                f"{' and '.join(str(self.lines[i]) for i in rows)}")
            elif rows and rows[0] in matched:
                problems.append(f"the row on line {self.lines[rows[0]]} matches two submissions: "
                                f"{matched[rows[0]].ident} and {submission.ident}")
            elif rows:
                matched[rows[0]] = submission
            else:
                unmatched.append(submission)
        if problems:
            raise RosterError(f"--roster {self.path}: " + "; ".join(problems)
                              + " (rename a submission, or correct the roster, so that each student is one row "
                                "and one submission)")
        return matched, unmatched


def read_roster(path: Path) -> Roster:
    """The class list, checked before anything is graded: an id or e-mail column, every row no wider
    than the header, and no id, user name or e-mail on two rows (naming both lines)."""
    records = read_csv(path, "--roster")
    if not records:
        raise RosterError(f"--roster {path}: the file is empty")
    header_line, headers = records[0][0], [h.strip() for h in records[0][1]]
    columns = {role: found for role, names in ROLES.items()
               if (found := list(dict.fromkeys(h for h in headers if normal(h) in names)))}
    roster = Roster(path, headers, [], [], columns)
    if not roster.keys:
        raise RosterError(f"--roster {path}: no id or e-mail column (looked for headers such as id, student id, "
                          f"ID number, SIS User ID, username, login, email, e-mail; found: {', '.join(headers)})")
    seen: dict[tuple[str, str], int] = {}
    for line, fields in records[1:]:
        if len(fields) > len(headers):
            raise RosterError(f"--roster {path}: line {line} has {len(fields)} fields, the header (line "
                              f"{header_line}) {len(headers)}: a field holding the separator must be quoted")
        cells = [f.strip() for f in fields]  # a Canvas export's rows that are not students: skipped
        if "points possible" in cells[0].lower() or all(re.fullmatch(r"(muted|manual posting.*)?", c, re.I)
                                                          for c in cells):  # "Muted" or "Manual Posting"
            continue
        row: dict[str, str] = {}
        for h, value in zip(headers, fields):
            row.setdefault(h, value.strip())
        for key in roster.keys:  # (a row without any stays: a student listed as missing, never dropped)
            if (value := row.get(key, "").casefold()) and (first := seen.setdefault((key, value), line)) != line:
                raise RosterError(f"--roster {path}: lines {first} and {line} have the same {key} "
                                  f"'{row[key]}'; each student must be one row (one of the two would get no grade)")
        roster.rows.append(row)
        roster.lines.append(line)
    return roster


@dataclass
class Outcome:
    ident: str
    status: str = "missing"
    total: float | None = None
    max_score: float = 0.0
    lessons: dict[str, dict] = field(default_factory=dict)        # NN -> status, score, max_score (hidden included)
    visible: dict[str, tuple[float, float]] = field(default_factory=dict)  # NN -> (score, max) of the visible tests
    has_hidden: bool = False
    tests: dict[str, float] = field(default_factory=dict)
    notes: list[str] = field(default_factory=list)          # for the instructor (grades.csv)
    student_notes: list[str] = field(default_factory=list)  # also for the student (the gradebooks' feedback)
    seconds: float = 0.0
    roster: dict[str, str] = field(default_factory=dict)
    line: int | None = None  # the roster's line, if a row matched

    @property
    def graded(self) -> bool:
        return self.status in ("graded", "partly gradable") and self.total is not None

    def describe(self) -> str:
        if not self.graded:
            return self.status
        percent = 100.0 * self.total / self.max_score if self.max_score else 0.0
        return f"{number(self.total)}/{number(self.max_score)} ({percent:.0f}%)" + (
            f", {self.status}" if self.status != "graded" else "")


def number(x: float | None) -> str:
    """A score as a gradebook reads it: no exponent, no binary noise (0.1 + 0.2 is 0.3)."""
    return "" if x is None else f"{round(x, 6):.15g}"


def feedback(o: Outcome) -> str:
    """What the gradebooks show the student: per lesson the score of the visible tests only, never a
    total or a lesson score that counts hidden tests (which results.json hides from students too)."""
    if o.status == "missing":
        return "no submission"
    if o.status == "grader error":
        return "not graded yet: the grader failed (not your work's fault); your instructor will grade it again"
    if o.status == "not gradable":
        return "not gradable: " + ("; ".join(o.student_notes) or "none of your files compiled")
    lessons = ", ".join(f"lesson {nn}: not gradable" if _not_gradable(o.lessons[nn]) else
                        "lesson {}: {}/{}".format(nn, *map(number, o.visible.get(nn, (0.0, 0.0))))
                        for nn in sorted(o.lessons))
    if o.has_hidden:
        score, top = (sum(pair[i] for pair in o.visible.values()) for i in (0, 1))
        head = f"visible tests {number(score)}/{number(top)} ({lessons}); hidden tests are graded too and count in " \
               "the grade"
    else:
        head = f"{number(o.total)}/{number(o.max_score)} ({lessons})"
    return "; ".join([head, *o.student_notes])


def _not_gradable(lesson: dict) -> bool:
    return lesson.get("status") == "not gradable"


def grades_rows(outcomes: list[Outcome], lessons: list[str], roster: Roster | None) -> list[list[str]]:
    """grades.csv, for the instructor: everything, hidden tests included."""
    tests = list(dict.fromkeys(name for o in outcomes for name in o.tests))  # in order of first appearance
    extra = [h for h in (roster.headers if roster else []) if h]
    rows = [["id", *[f"roster: {h}" for h in extra], "status", "total", "max", *[f"lesson{nn}" for nn in lessons],
             *tests, "notes"]]
    for o in outcomes:
        lesson_cells = ["" if (info := o.lessons.get(nn)) is None else "not gradable" if _not_gradable(info)
                        else number(float(info.get("score", 0))) for nn in lessons]
        test_cells = ["" if name not in o.tests or ((lesson := re.match(r"lesson(\d\d)", name))
                                                    and _not_gradable(o.lessons.get(lesson.group(1), {})))
                      else number(o.tests[name]) for name in tests]
        rows.append([o.ident, *[o.roster.get(h, "") for h in extra], o.status, number(o.total),
                     number(o.max_score) if o.lessons else "", *lesson_cells, *test_cells, "; ".join(o.notes)])
    return rows


def _looks(idents: list[str]) -> str:
    """What folder names are, without a roster: e-mails, numbers (ID numbers), else user names."""
    if idents and all("@" in i for i in idents):
        return "email"
    return "idnumber" if idents and all(i.isdigit() for i in idents) else "username"


def moodle_rows(outcomes: list[Outcome], roster: Roster | None, assignment: str) -> tuple[list[list[str]], list[str]]:
    """Moodle's grade import (Grades > Import > CSV file; docs/grading.md): the rows, and what was left out and why."""
    if roster is None:
        role = _looks([o.ident for o in outcomes])
    else:  # the identity the roster fills on the most rows; on a tie e-mail, then ID number, then user name
        rows = [o.roster for o in outcomes if o.line is not None]
        role = max(("email", "idnumber", "username"), key=lambda r: sum(bool(roster.value(row, r)) for row in rows))
    rows, left_out = [[MOODLE_HEADERS[role], "Full name", assignment, f"{assignment} (feedback)"]], []
    for o in outcomes:
        user = o.ident if roster is None else roster.value(o.roster, role) if o.line is not None else ""
        if user:
            rows.append([user, roster.names(o.roster)[0] if roster else "", number(o.total) if o.graded else "",
                         feedback(o)])
        else:
            left_out.append(f"{o.ident}: " + ("no row of the roster matches this submission" if o.line is None else
                                              f"the roster's line {o.line} has no {MOODLE_HEADERS[role].lower()}"))
    return rows, left_out


def canvas_rows(outcomes: list[Outcome], roster: Roster | None, assignment: str) -> tuple[list[list[str]], list[str]]:
    """Canvas's gradebook import, after a "Points Possible" row: the rows, and what was left out and why."""
    rows = [["Student", "ID", "SIS User ID", "SIS Login ID", "Section", assignment],
            ["Points Possible", "", "", "", "", number(max((o.max_score for o in outcomes), default=0.0))]]
    left_out: list[str] = []
    numbers = _looks([o.ident for o in outcomes]) == "idnumber"  # without a roster: SIS User IDs, else logins
    for o in outcomes:
        grade = number(o.total) if o.graded else ""
        if roster is None:  # the folder names are all there is
            rows.append([o.ident, "", o.ident if numbers else "", "" if numbers else o.ident, "", grade])
            continue
        if o.line is None:
            left_out.append(f"{o.ident}: no row of the roster matches this submission")
            continue
        canvas_id = roster.value(o.roster, "id") if roster.from_canvas else ""
        login = roster.value(o.roster, "username") or roster.value(o.roster, "email")
        rows.append([roster.names(o.roster)[1], canvas_id, roster.value(o.roster, "idnumber"), login,
                     roster.value(o.roster, "section"), grade])
    return rows, left_out
