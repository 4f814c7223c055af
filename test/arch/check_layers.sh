#!/bin/sh
# The layers of Lignum's sources, checked on the object files (nm):
#   check_layers.sh <architecture.md> <src dir> <object files...>
# doc/architecture.md's table gives each source file its layer (a row
# "| N | `file.c` | ..."). A call (an undefined symbol of one object that
# another object defines) must go to a file of the same or a lower layer,
# and the graph of calls between files must have no circle. Files of the
# pure-helper layers (0 to 2) must not see the integrator's memory record
# (no lgn_impl.h, no LGNMem). Every object must have a row, and every row
# an object, except the rows named in the environment variable
# LGN_LAYERS_NOT_BUILT (space separated: files the build configuration
# leaves out, e.g. lgn_klu_solve.c without KLU). Exits 1 with one line per
# violation.
set -eu
notbuilt=${LGN_LAYERS_NOT_BUILT:-}
doc=$1
src=$2
shift 2
tmp=${TMPDIR:-/tmp}/lgn_layers.$$
mkdir -p "$tmp"
trap 'rm -rf "$tmp"' EXIT

# layer table: "file rank"
sed -n 's/^| *\([0-9][0-9]*\) *| *`\([^`]*\.c\)`.*$/\2 \1/p' "$doc" > "$tmp/ranks"
if [ ! -s "$tmp/ranks" ]; then
  echo "check_layers: no layer table found in $doc"
  exit 1
fi

# per object: its source file (relative to src/, from the object's path)
: > "$tmp/defs"
: > "$tmp/uses"
: > "$tmp/files"
for o in "$@"; do
  f=$(printf '%s\n' "$o" | sed 's|.*\.dir/||; s|\.o$||; s|\.obj$||')
  echo "$f" >> "$tmp/files"
  nm "$o" | awk -v f="$f" '$2 ~ /^[TDBR]$/ { print $3, f }' >> "$tmp/defs"
  nm "$o" | awk -v f="$f" '$1 == "U" { print $2, f }' >> "$tmp/uses"
done

awk -v tmp="$tmp" -v notbuilt="$notbuilt" '
  BEGIN { nnb = split(notbuilt, nb, " "); for (i = 1; i <= nnb; i++) skip[nb[i]] = 1 }
  FILENAME == tmp "/ranks" { rank[$1] = $2; inrow[$1] = 1; next }
  FILENAME == tmp "/files" { file[$1] = 1; next }
  FILENAME == tmp "/defs"  { def[$1] = $2; next }
  FILENAME == tmp "/uses"  {
    if (!($1 in def) || def[$1] == $2) next
    e = $2 SUBSEP def[$1]
    if (!(e in edge)) { edge[e] = $1; n[$2]++; adj[$2, n[$2]] = def[$1] }
    next
  }
  END {
    bad = 0
    for (f in file) if (!(f in rank)) {
      print "check_layers: " f " has no layer in the table"; bad = 1 }
    for (f in rank) if (!(f in file) && !(f in skip)) {
      print "check_layers: the table lists " f ", which is not built"; bad = 1 }
    for (e in edge) {
      split(e, p, SUBSEP)
      if ((p[1] in rank) && (p[2] in rank) && rank[p[2]] + 0 > rank[p[1]] + 0) {
        print "check_layers: upward call " p[1] " (layer " rank[p[1]] ") -> " \
              p[2] " (layer " rank[p[2]] ") through " edge[e]
        bad = 1
      }
    }
    # circles: depth-first search, state 1 = on the path, 2 = done
    for (f in file) {
      if (state[f]) continue
      top = 1; stack[1] = f; it[1] = 0; state[f] = 1
      while (top > 0) {
        u = stack[top]
        if (it[top] < n[u]) {
          it[top]++; w = adj[u, it[top]]
          if (state[w] == 1) {
            path = w
            for (k = top; k >= 1 && stack[k] != w; k--) path = stack[k] " -> " path
            print "check_layers: circle " w " -> " path; bad = 1
          } else if (!state[w]) {
            top++; stack[top] = w; it[top] = 0; state[w] = 1
          }
        } else { state[u] = 2; top-- }
      }
    }
    exit bad
  }' "$tmp/ranks" "$tmp/files" "$tmp/defs" "$tmp/uses" || status=1

# pure helpers (layers 0..2) never see the memory record
while read -r f r; do
  if [ "$r" -le 2 ] && [ -f "$src/$f" ] &&
     grep -n -E '#include *"lgn_impl\.h"|\<LGNMem\>|struct LGNMemRec' "$src/$f" > "$tmp/grep"; then
    echo "check_layers: $f is a pure helper (layer $r) but sees the memory record:"
    sed 's/^/    /' "$tmp/grep"
    status=1
  fi
done < "$tmp/ranks"

if [ "${status:-0}" -ne 0 ]; then exit 1; fi
echo "check_layers: $(wc -l < "$tmp/files") files, no upward call, no circle"
