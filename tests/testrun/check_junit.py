# Reads the JUnit XML of `tmclrun --test` (tests/golden/testrun: the suite and a bad test file) as
# CI tools do and checks what they would show: with xml.etree (Python's own), or with
# junitparser (Debian's python3-junitparser, what many CI scripts use) when given --junitparser.
# Exit status 0 when every check holds; a message on standard error for each that does not.
import sys

path = sys.argv[1]
problems = []


def expect(what, got, want):
    if got != want:
        problems.append(f"{what}: got {got!r}, expected {want!r}")


if "--junitparser" in sys.argv:
    from junitparser import JUnitXml, Failure, Error, Skipped

    xml = JUnitXml.fromfile(path)
    suites = list(xml)
    expect("testsuites", len(suites), 1)
    suite = suites[0]
    expect("tests", suite.tests, 4)
    expect("failures", suite.failures, 1)
    expect("errors", suite.errors, 1)
    expect("skipped", suite.skipped, 1)
    cases = {case.name: case for case in suite}
    expect("testcases", sorted(cases), ["fail", "pass", "program", "skip"])
    expect("pass result", cases["pass"].result, [])
    kinds = {name: [type(r).__name__ for r in case.result] for name, case in cases.items()}
    expect("fail result", kinds["fail"], ["Failure"])
    expect("program result", kinds["program"], ["Error"])
    expect("skip result", kinds["skip"], ["Skipped"])
    failure = cases["fail"].result[0]
    if "got 6" not in failure.message or "prog.tmc:10" not in (failure.text or ""):
        problems.append(f"failure: {failure.message!r} / {failure.text!r}")
    expect("classname", cases["pass"].classname, "suite")
    if not isinstance(cases["fail"].time, float) or cases["fail"].time < 0:
        problems.append(f"fail time {cases['fail'].time!r} is not seconds")
else:
    import xml.etree.ElementTree as ET

    root = ET.parse(path).getroot()
    expect("root", root.tag, "testsuites")
    suites = root.findall("testsuite")
    expect("testsuites", len(suites), 1)
    suite = suites[0]
    for key, want in {"tests": "4", "failures": "1", "errors": "1", "skipped": "1"}.items():
        expect(key, suite.get(key), want)
        expect("testsuites " + key, root.get(key), want)
    cases = suite.findall("testcase")
    expect("names", [c.get("name") for c in cases], ["fail", "pass", "skip", "program"])
    expect("files", [c.get("file") for c in cases],
           ["suite/fail.tmctest", "suite/pass.tmctest", "suite/skip.tmctest", "bad/program.tmctest"])
    for c in cases:
        float(c.get("time"))  # seconds as a decimal number
    import datetime
    datetime.datetime.strptime(suite.get("timestamp"), "%Y-%m-%dT%H:%M:%S")
    fail = cases[0].find("failure")
    expect("failure type", fail.get("type"), "expectation")
    if "suite/fail.tmctest:4: expected acc = 5 at 1ms, got 6" not in fail.text:
        problems.append(f"failure text: {fail.text!r}")
    if "v[1] >= 2" not in fail.text:  # &gt; read back as >
        problems.append(f"failure text not unescaped: {fail.text!r}")
    expect("pass children", list(cases[1]), [])
    expect("skipped", cases[2].find("skipped").get("message"), "waits for a module with two motors")
    error = cases[3].find("error")
    if "unknown instruction mnemonic 'SAPP'" not in error.text:
        problems.append(f"error text: {error.text!r}")

for p in problems:
    print(p, file=sys.stderr)
sys.exit(1 if problems else 0)
