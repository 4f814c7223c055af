#!/bin/sh
# Who writes the integrator record's sub-records, checked on the sources:
#   check_owners.sh <architecture.md> <src dir>
# doc/architecture.md's owners table gives each sub-record of LGNMemRec
# (lgn_impl.h) the files that may write its fields, a row
# "| `sub` | `struct LGNxxxRec` | `file.c`, `file.c` ... | what it holds |".
# A write is an assignment (=, +=, -=, *=, /=, |=, &=, ^=, <<=, >>=) to, or
# an increment (++, --) of, `->sub.field` (or an element of it): reading,
# taking the address and writing into an array the field points to are not
# writes of the field. Files are named by their base name (a move between
# folders keeps the table right). Exits 1 with one line per write by a file
# that is not among the owners, or when the table is missing.
set -eu
doc=$1
src=$2
tmp=${TMPDIR:-/tmp}/lgn_owners.$$
mkdir -p "$tmp"
trap 'rm -rf "$tmp"' EXIT

# owners table: "sub file file ..."
sed -n 's/^| *`\([a-z][a-z0-9_]*\)` *| *`struct LGN[A-Za-z0-9]*Rec` *| *\([^|]*\)|.*$/\1 \2/p' "$doc" |
  sed 's/[`,]/ /g; s/  */ /g' > "$tmp/owners"
if [ ! -s "$tmp/owners" ]; then
  echo "check_owners: no owners table found in $doc"
  exit 1
fi

find "$src" -name '*.c' | sort > "$tmp/files"
status=0
while read -r f; do
  base=$(basename "$f")
  awk -v base="$base" -v path="$f" -v ownfile="$tmp/owners" '
    BEGIN {
      while ((getline line < ownfile) > 0) {
        n = split(line, w, " ")
        subs[w[1]] = 1
        names[w[1]] = ""
        for (i = 2; i <= n; i++) {
          own[w[1], w[i]] = 1
          names[w[1]] = names[w[1]] (i > 2 ? ", " : "") w[i]
        }
      }
      bad = 0; incom = 0
    }
    {
      line = $0
      # drop comments (also those spanning lines) and string literals
      out = ""
      while (line != "") {
        if (incom) {
          k = index(line, "*/")
          if (k == 0) { line = ""; break }
          line = substr(line, k + 2); incom = 0
        } else {
          k = index(line, "/*"); c = index(line, "//")
          if (c > 0 && (k == 0 || c < k)) { out = out substr(line, 1, c - 1); line = ""; break }
          if (k == 0) { out = out line; line = ""; break }
          out = out substr(line, 1, k - 1); line = substr(line, k + 2); incom = 1
        }
      }
      gsub(/"([^"\\]|\\.)*"/, "\"\"", out)
      s = out
      # postfix / compound / plain assignments and prefix increments
      while (match(s, /->[a-z][a-z0-9_]*\.[A-Za-z_][A-Za-z0-9_]*(\[[^]]*\])*[ \t]*(\+\+|--|([-+*\/|&^]|<<|>>)?=[^=])/) ||
             match(s, /(\+\+|--)[ \t]*[A-Za-z_][A-Za-z0-9_]*(\)|->[a-z][a-z0-9_]*)*->[a-z][a-z0-9_]*\.[A-Za-z_][A-Za-z0-9_]*/)) {
        hit = substr(s, RSTART, RLENGTH)
        s = substr(s, RSTART + RLENGTH)
        h = hit
        sub(/^(\+\+|--)[ \t]*/, "", h)
        # the last ->sub.field of the hit
        n = split(h, parts, "->")
        ref = parts[n]
        split(ref, sf, ".")
        sb = sf[1]
        fld = sf[2]; sub(/[^A-Za-z0-9_].*$/, "", fld)
        if (!(sb in subs)) continue
        if (!((sb, base) in own)) {
          printf "check_owners: %s:%d writes ->%s.%s; the owners of %s are %s\n",
                 path, NR, sb, fld, sb, names[sb]
          bad = 1
        }
      }
    }
    END { exit bad }' "$f" || status=1
done < "$tmp/files"

if [ "$status" -ne 0 ]; then exit 1; fi
echo "check_owners: $(wc -l < "$tmp/files") files, $(wc -l < "$tmp/owners") sub-records, every write by an owner"
