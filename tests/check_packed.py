"""Packing in C files (tests/check_sizes.sh): lines over 100 columns (tabs
to 8) and comma-operator chains (a statement whose top level holds a comma
and that is not a declaration), one "FILE:LINE: long|comma" per finding."""
import re
import sys
DECL = re.compile(r'^\s*(?!return\b)(?:[A-Za-z_]\w*\s+)+\**\s*[A-Za-z_]\w*\s*(?:=|,|;|\[)'
                  r'|^\s*(?:const|static|unsigned|signed|struct|enum|double|float|int|long|char|short|size_t|'
                  r'u?int\d+_t|FILE|json_object|bool|void)\b')
def strip(t):
    t = re.sub(r'"(?:[^"\\]|\\.)*"', '""', t)
    t = re.sub(r"'(?:[^'\\]|\\.)*'", "''", t)
    t = re.sub(r'/\*.*?\*/', '', t)
    prev = None
    while prev != t:
        prev = t
        t = re.sub(r'\([^()\[\]{}]*\)|\[[^()\[\]{}]*\]|\{[^()\[\]{}]*\}', '', t)
    return t
def starts_statement(prev):
    p = re.sub(r'/\*.*?\*/', '', prev).rstrip()
    return (p == '' or p.endswith((';', '{', '}', ':')) or p.strip() == 'else'
            or re.match(r'^\s*(if|for|while|else if|switch)\b.*\)$', p) is not None)
for path in sys.argv[1:]:
    prev = ''
    for n, line in enumerate(open(path).read().split('\n'), 1):
        if len(line.expandtabs(8)) > 100:
            print('%s:%d: long' % (path, n))
        t = line.strip()
        code = t and not t.startswith(('#', '* ', '*/', '/*', '//')) and t != '*'
        if code:
            s = strip(line)
            if (s.rstrip().endswith(';') and ',' in s and not DECL.match(s) and not re.search(r'[(){}\[\]]', s)
                    and starts_statement(prev)):
                print('%s:%d: comma' % (path, n))
            prev = line
