"""Build a hostile class folder: what real submission folders hold, and what a prankster adds.

Deterministic and small (a few hundred KiB on disk; one sparse "huge" file), generated into a
folder rather than stored, because most of it cannot live in git: FIFOs, links to devices and
outside the folder, file names that are not UTF-8, permissions.

    python tests/data/hostile/make_corpus.py OUT_DIR

Every student answers the pendulum problem (``bowling_3_15_4_pendulum``: ``acc_mag`` scalar,
``acc_N`` vector, ``acc_mag_symbolic`` symbolic) so every answer reaches the grader.
:data:`EXPECTED_SKIPPED` names the entries that must come out as skipped, not as students.
"""

from __future__ import annotations

import json
import os
import sys
from pathlib import Path

P = "bowling_3_15_4_pendulum"
GOOD = {f"{P}.acc_mag": "98.5 ft/s^2", f"{P}.acc_N": "(-89.9, -40.3) ft/s^2",
        f"{P}.acc_mag_symbolic": "L*sqrt(thetadd^2 + thetad^4)"}

# Answer texts that attack the reader: code, resource bombs, encodings, Unicode tricks.
HOSTILE_ANSWERS = [
    "__import__('os').system('touch PWNED')",
    "().__class__.__bases__[0].__subclasses__()",
    "eval('1+1')", "exec('x=1')", "lambda: 0", "[x for x in ()]", "f'{1}'",
    "9**9**9**9", "10^10^10^10", "exp(exp(exp(100)))", "factorial(10**9)",
    "1e308*1e308", "-" * 5000 + "1", "(" * 3000 + "1" + ")" * 3000, "9" * 5000,
    "x" * 100_000, "1" + "0" * 4300 + " m",
    "98.5.0", "98..5", "1 000 m", "98.5 ft//s^2", "(-66, -40#)", "98.5\r\n30 m/s^2",
    "98.5\u2029ft/s^2", "\u202e2s/tf 5.89", "９８.５ ft/s²", "98\u200b.5 ft/s^2",
    "98,5 ft/s^2", "NaN", "inf ft/s^2", "-0", "", "   ", "\t\x0b\x0c",
    "<script>alert('x')</script>", "=HYPERLINK(\"http://evil\")", "@SUM(A1)", "+1-1",
    "'; DROP TABLE students; --", "{{ 7*7 }}", "{% raw %}", "${7*7}", "\\input{/etc/passwd}",
    "\x1b[31mred\x1b[0m", "\x07\x7f\x85\x9b", "\ud800", "\udce9", "😀 m/s", "Ω·m",
]


def _write(path: Path, data: bytes | str) -> None:
    path.parent.mkdir(parents=True, exist_ok=True)
    if isinstance(data, str):
        data = data.encode("utf-8", "surrogatepass")
    path.write_bytes(data)


def _txt(answers: dict[str, str]) -> str:
    return "".join(f"{key} = {value}\n" for key, value in answers.items())


def build(root: str | Path) -> Path:
    """Write the corpus into ``root`` (created); returns ``root``."""
    root = Path(root).absolute()  # links are made absolute, so they work from anywhere
    root.mkdir(parents=True, exist_ok=True)
    broot = os.fsencode(root)

    # Plain good students, in each format, so the run has something to grade.
    _write(root / "ana" / "answers.yaml", "".join(f"{k}: '{v}'\n" for k, v in GOOD.items()))
    _write(root / "ben.json", json.dumps(GOOD))
    _write(root / "cy.txt", _txt(GOOD))

    # One student per hostile answer (JSON keeps every string exactly, even lone surrogates).
    for i, text in enumerate(HOSTILE_ANSWERS):
        body = json.dumps({f"{P}.acc_mag": text, f"{P}.acc_N": text,
                           f"{P}.acc_mag_symbolic": text}, ensure_ascii=True)
        _write(root / f"answer_{i:02d}.json", body)

    # The YAML parser's limits.
    _write(root / "yaml_deep.yaml", f"{P}.acc_mag: " + "[" * 5000 + "]" * 5000 + "\n")
    _write(root / "yaml_deep_map.yaml", "".join(" " * i + "a:\n" for i in range(2000)))
    _write(root / "yaml_control.yaml", f"{P}.acc_mag: \"98.5\x07\x1b\x7f\x85\x9b\"\n")
    _write(root / "yaml_control_plain.yaml", f"{P}.acc_mag: 98.5\x07 ft/s^2\n")
    _write(root / "yaml_noncharacter.yaml", f"{P}.acc_mag: 98.5\ufffe ft/s^2\n")
    _write(root / "yaml_surrogate.yaml", f"{P}.acc_mag: '98.5\ud800'\n")
    _write(root / "yaml_bigint.yaml", f"{P}.acc_mag: {'9' * 5000}\n")
    _write(root / "yaml_bigfloat.yaml", f"{P}.acc_mag: {'9' * 5000}.5e99999\n")
    _write(root / "yaml_tags.yaml", f"{P}.acc_mag: !!python/object/apply:os.system ['touch PWNED']\n")
    _write(root / "yaml_alias.yaml", "a: &a [1, 2]\nb: *a\n")
    _write(root / "yaml_laughs.yaml", "a: &a ['lol','lol']\nb: &b [*a,*a,*a]\nc: &c [*b,*b,*b]\n")
    _write(root / "yaml_dupkey.yaml", f"{P}.acc_mag: 1\n{P}.acc_mag: 2\n")
    _write(root / "yaml_tab.yaml", f"{P}:\n\tacc_mag: 98.5\n")
    _write(root / "yaml_list.yaml", f"{P}.acc_N:\n  - -66 i - 40 j\n")
    _write(root / "yaml_doc_stream.yaml", f"{P}.acc_mag: 1\n---\n{P}.acc_mag: 2\n")
    _write(root / "yaml_not_mapping.yaml", "- just\n- a list\n")
    _write(root / "json_deep.json", "[" * 100_000 + "]" * 100_000)
    _write(root / "json_bigint.json", json.dumps({f"{P}.acc_mag": 1})[:-2] + "9" * 5000 + "}")
    _write(root / "json_nan.json", '{"%s.acc_mag": NaN}' % P)
    _write(root / "json_nested_answer.json", json.dumps({P: {"acc_mag": {"x": [1, {"y": 2}]}}}))
    _write(root / "txt_many.txt", "".join(f"k{i} = {i}\n" for i in range(2000)))
    _write(root / "txt_long_line.txt", f"{P}.acc_mag = " + "1" * 200_000 + "\n")

    # Encodings.
    _write(root / "enc_utf16.txt", b"\xff\xfe" + _txt(GOOD).encode("utf-16-le"))
    _write(root / "enc_utf16_bad.txt", b"\xff\xfe\x00\xd8\x41\x00")
    _write(root / "enc_utf32.txt", _txt(GOOD).encode("utf-32"))
    _write(root / "enc_latin1.txt", f"{P}.acc_mag = 98.5 ft/s² é\n".encode("latin-1"))
    _write(root / "enc_cp1252.txt", f"{P}.acc_mag = 98.5 ft/s² – ok\n".encode("cp1252"))
    _write(root / "enc_bom_middle.txt", _txt(GOOD).replace("\n", "\ufeff\n", 1))
    _write(root / "enc_cr_only.txt", _txt(GOOD).replace("\n", "\r"))
    _write(root / "enc_binary.txt", bytes(range(256)) * 4)
    _write(root / "enc_invalid_utf8.yaml", b"k: \xc3\x28\xa0\xa1\n")

    # Unicode tricks in keys and names.
    _write(root / "uni_homoglyph.txt", f"{P}.асс_mag = 98.5 ft/s^2\n")  # Cyrillic а, с
    _write(root / "uni_rtl.txt", f"{P}.acc_mag = \u202e98.5\n")
    _write(root / "Zo\u00eb.txt", _txt(GOOD))
    _write(root / "Zoe\u0308.txt", _txt(GOOD))
    _write(root / " spaced .txt", _txt(GOOD))
    _write(root / "emoji😀.txt", _txt(GOOD))
    _write(root / "new\nline.txt", _txt(GOOD))
    _write(root / "-rf.txt", _txt(GOOD))
    _write(root / "--help", b"")  # a stray file, not a submission
    _write(root / "CON.txt", _txt(GOOD))
    _write(root / "<img src=x onerror=alert(1)>.txt", _txt(GOOD))
    _write(root / "=HYPERLINK(1).txt", _txt(GOOD))
    _write(root / ("long" * 60 + ".txt"), _txt(GOOD))
    os.makedirs(os.path.join(broot, b"bad\xe9name"), exist_ok=True)
    with open(os.path.join(broot, b"bad\xe9name", b"answers.txt"), "w", encoding="utf-8") as f:
        f.write(_txt(GOOD))
    with open(os.path.join(broot, b"bytes\xff\xfe.txt"), "w", encoding="utf-8") as f:
        f.write(_txt(GOOD))

    # Look-alike answer files and folder clutter.
    _write(root / "dee" / "Answers.YAML", "".join(f"{k}: '{v}'\n" for k, v in GOOD.items()))
    _write(root / "dee" / "answers.yml", f"{P}.acc_mag: 1 ft/s^2\n")
    _write(root / "dee" / ".DS_Store", b"\x00\x01")
    _write(root / "dee" / "work.pdf", b"%PDF-1.4")
    _write(root / "__MACOSX" / "._ana", b"\x00")
    _write(root / ".DS_Store", b"\x00\x00\x00\x01Bud1")
    _write(root / ".git" / "HEAD", "ref: refs/heads/main\n")
    _write(root / "Thumbs.db", b"\x00")
    _write(root / "notes.pdf", b"%PDF")
    (root / "empty_folder").mkdir(exist_ok=True)
    _write(root / "nested" / "hw1" / "answers.txt", _txt(GOOD))
    (root / "answers.yaml_dir" / "answers.yaml").mkdir(parents=True, exist_ok=True)

    # Amplification: what one file or folder repeats must not be repeated in every output.
    _write(root / "amp_repeated.txt", _filled(lambda i: f"{P}.acc_mag = 98.5 ft/s^2\n"))
    _write(root / "amp_garbage.txt", _filled(lambda i: "not an answer\n"))
    _write(root / "amp_json_keys.json",
           "{" + _filled(lambda i: f'"k{i % 500}": {i}, ') + '"end": 0}')
    _write(root / "amp_not_text.json",
           "{" + _filled(lambda i: f'"{P}.k{i}": [[{i}]], ') + '"end": 0}')
    _write(root / "amp_stray" / "answers.txt", _txt(GOOD))
    for i in range(STRAY_FILES):
        _write(root / "amp_stray" / f"scan{i:05d}.pdf", b"")

    # Terminal control sequences in names the summary prints (skipped entries): shown escaped.
    for name in TERMINAL_NAMES:
        _write(root / name, b"")

    # Roster conflicts (ROSTER): 'CY.txt' and 'cy.txt' both name Cy; '101.txt' is named with
    # Dee's roster id while her own folder 'dee' names her by her email.
    _write(root / "CY.txt", _txt(GOOD))
    _write(root / "101.txt", _txt(GOOD))

    # File-system tricks.
    outside = root.parent / f"{root.name}_outside"
    _write(outside / "secret.txt", _txt(GOOD))
    _link(outside / "secret.txt", root / "link_outside.txt")
    _link(outside, root / "link_outside_dir")
    _link(Path("/dev/zero"), root / "link_devzero.txt")
    _link(Path("/dev/zero"), root / "devzero_in" / "answers.txt")
    _link(root / "nowhere.txt", root / "dangling.txt")
    _link(root / "loop_b", root / "loop_a")
    _link(root / "loop_a", root / "loop_b")
    _link(root / "ana" / "answers.yaml", root / "copycat" / "answers.yaml")
    _link(root / "ben.json", root / "copycat2.json")
    _link(root / "ana", root / "ana_again")
    (root / "fifo_in").mkdir(exist_ok=True)
    _fifo(root / "fifo_in" / "answers.txt")
    _fifo(root / "fifo.txt")
    sparse = root / "sparse.txt"
    with open(sparse, "wb") as handle:
        handle.truncate(8 * 1024 ** 3)  # 8 GiB on paper, nothing on disk
    _write(root / "locked" / "answers.txt", _txt(GOOD))
    os.chmod(root / "locked" / "answers.txt", 0)
    _write(root / "locked_dir" / "answers.txt", _txt(GOOD))
    os.chmod(root / "locked_dir", 0)
    return root


def _filled(piece) -> str:
    """``piece(0) + piece(1) + ...`` as long as it stays a little below the answers file cap."""
    out, size, i = [], 0, 0
    while size + len(piece(i)) < MAX_BYTES - 64:
        out.append(piece(i))
        size += len(out[-1])
        i += 1
    return "".join(out)


def _link(target: Path, link: Path) -> None:
    link.parent.mkdir(parents=True, exist_ok=True)
    if not os.path.lexists(link):
        os.symlink(target, link)


def _fifo(path: Path) -> None:
    if not os.path.lexists(path):
        os.mkfifo(path)


MAX_BYTES = 256 * 1024  # the size cap of an answers file
STRAY_FILES = 3000
TERMINAL_NAMES = ("\x1b]0;owned\x07title.pdf", "\x1b[2J\x1b[8mhidden.pdf", "\rcr.pdf",
                  "\x9b31mred.pdf")
ROSTER = """id,name,email
ana,Ana Able,ana@uni.edu
cy,Cy Cole,cy@uni.edu
101,Dee Dunn,dee@uni.edu
nobody,No Body,nobody@uni.edu
"""
"""A roster for the class: Ana matches one folder, Cy and Dee are in roster conflicts, No Body
handed in nothing."""

EXPECTED_SKIPPED = {
    ".DS_Store", ".git", "Thumbs.db", "notes.pdf", "__MACOSX", "--help", "dangling.txt",
    "fifo.txt", "dee/.DS_Store", "dee/work.pdf", "nested/hw1",
}
"""Entries that must be listed as skipped (a subset: links and loops are reported as well)."""


def unlock(root: str | Path) -> None:
    """Give back the permissions :func:`build` took away, so the folder can be deleted."""
    root = Path(root)
    for path in (root / "locked_dir", root / "locked" / "answers.txt"):
        if path.exists():
            os.chmod(path, 0o755)


if __name__ == "__main__":
    if len(sys.argv) != 2:
        sys.exit("usage: make_corpus.py OUT_DIR")
    print(build(sys.argv[1]))
