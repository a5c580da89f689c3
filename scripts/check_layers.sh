#!/usr/bin/env bash
# Layering check (CTest: Layers.IncludesMatchLinks). Usage: check_layers.sh [SOURCE_DIR]
#
# The stages are the static libraries CMakeLists.txt declares with
#   penink_stage(<target> <dir> <deps...>)        (a call may span several lines)
# plus penink_cli (sources src/cli, declared with add_library) and any
#   target_link_libraries(<stage> [PUBLIC|PRIVATE|INTERFACE] <deps...>)
# on one of those targets. Only dependencies named penink_* are part of the layer graph.
#
# Fails (exit 1, one line per problem) when
#  1. a .hpp/.cpp in a stage's folder has a project include "<stage>/..." (core input surface
#     drainage lines render export scene preview cli) naming a stage that is neither its own nor in its
#     stage's transitive link closure (the include compiles only by accident of include paths);
#  2. a stage links a stage directly that none of its files includes (a stale or redundant link);
#  3. the link graph has a cycle, the CMake file cannot be parsed, or a stage folder is missing.
# Tests, benchmarks and test support are out of scope. Needs bash 4, grep, sed, tr, coreutils.
set -u

root=${1:-$(cd "$(dirname "$0")/.." && pwd)}
cmake_file=$root/CMakeLists.txt
[[ -f $cmake_file ]] || { echo "check_layers: no $cmake_file" >&2; exit 2; }

failures=0
fail() { echo "$*"; failures=$((failures + 1)); }

# The CMake file without comments, on one line, so calls spanning lines parse like one-liners.
flat=$(sed -e 's/#.*$//' "$cmake_file" | tr '\n\t' '  ')

declare -A dir_of deps_of   # stage target -> folder (relative to root); -> direct penink_* deps
declare -a stages=()

add_deps() {  # add_deps <target> <tokens...>: record the penink_* tokens as direct deps
    local t=$1 d
    shift
    for d in "$@"; do
        [[ $d == penink_* ]] || continue
        [[ " ${deps_of[$t]-} " == *" $d "* ]] || deps_of[$t]="${deps_of[$t]-} $d"
    done
}

while read -r call; do
    [[ -n $call ]] || continue
    read -ra args <<<"${call#penink_stage(}"
    args[-1]=${args[-1]%)}
    [[ -z ${args[-1]} ]] && unset 'args[-1]'
    if (( ${#args[@]} < 2 )); then
        fail "CMakeLists.txt: cannot parse '$call'"
        continue
    fi
    t=${args[0]}
    stages+=("$t")
    dir_of[$t]=${args[1]}
    deps_of[$t]=""
    add_deps "$t" "${args[@]:2}"
done < <(grep -oE 'penink_stage\([^)]*\)' <<<"$flat")

# penink_cli: an ordinary add_library over src/cli (main.cpp goes to the executable, which links
# penink_cli alone, so its includes answer to penink_cli's closure too).
if grep -qE 'add_library\( *penink_cli[ )]' <<<"$flat"; then
    stages+=(penink_cli)
    dir_of[penink_cli]=src/cli
    deps_of[penink_cli]=""
fi

while read -r call; do
    [[ -n $call ]] || continue
    read -ra args <<<"${call#target_link_libraries(}"
    args[-1]=${args[-1]%)}
    t=${args[0]}
    [[ -n ${dir_of[$t]-} ]] || continue  # not a stage (the executable, test support, benchmarks)
    add_deps "$t" "${args[@]:1}"
done < <(grep -oE 'target_link_libraries\([^)]*\)' <<<"$flat")

if (( ${#stages[@]} == 0 )); then
    echo "check_layers: no penink_stage(...) calls found in $cmake_file"
    exit 1
fi

# Transitive link closure of each stage (depth-first; a visited set makes cycles terminate).
declare -A closure
for s in "${stages[@]}"; do
    declare -A seen=()
    read -ra stack <<<"${deps_of[$s]}"
    while (( ${#stack[@]} )); do
        d=${stack[-1]}
        unset 'stack[-1]'
        [[ -n ${seen[$d]-} ]] && continue
        seen[$d]=1
        if [[ -z ${dir_of[$d]-} ]]; then
            fail "CMakeLists.txt: $s depends on $d, which is not a stage"
            continue
        fi
        read -ra more <<<"${deps_of[$d]}"
        stack+=("${more[@]}")
    done
    closure[$s]=" ${!seen[*]} "
    [[ -n ${seen[$s]-} ]] && fail "CMakeLists.txt: link cycle through $s"
    unset seen
done

# The stage a project include names (into $stage, "" for none): its first path component.
stage_of_include() {
    case $1 in
        core | input | surface | drainage | lines | render | export | scene | preview | cli) stage="penink_$1" ;;
        *) stage="" ;;
    esac
}

files_checked=0
for s in "${stages[@]}"; do
    dir=$root/${dir_of[$s]}
    if [[ ! -d $dir ]]; then
        fail "CMakeLists.txt: folder ${dir_of[$s]} of $s does not exist"
        continue
    fi
    declare -A included=()  # stages this stage's files include directly
    for f in "$dir"/*.hpp "$dir"/*.cpp; do
        [[ -f $f ]] || continue
        files_checked=$((files_checked + 1))
        rel=${f#"$root"/}
        while IFS= read -r hit; do
            line=${hit%%:*}
            [[ ${hit#*:} =~ \"([^\"]*)\" ]] || continue
            inc=${BASH_REMATCH[1]}
            [[ $inc == */* ]] || continue  # same-folder include ("dv_format.hpp")
            stage_of_include "${inc%%/*}"
            target=$stage
            [[ -n $target ]] || continue   # not a stage folder (third-party, test support)
            included[$target]=1
            [[ $target == "$s" ]] && continue
            if [[ ${closure[$s]} != *" $target "* ]]; then
                fail "$rel:$line: #include \"$inc\": $s does not link $target (links:${deps_of[$s]:- nothing})"
            fi
        done < <(grep -nE '^[[:space:]]*#[[:space:]]*include[[:space:]]*"' "$f")
    done
    for d in ${deps_of[$s]}; do
        [[ -n ${included[$d]-} ]] && continue
        fail "CMakeLists.txt: $s links $d, but no file in ${dir_of[$s]}/ includes \"${d#penink_}/...\""
    done
    unset included
done

if (( failures > 0 )); then
    echo "check_layers: $failures problem(s) in ${#stages[@]} stages, $files_checked files"
    exit 1
fi
echo "check_layers: ${#stages[@]} stages, $files_checked files: includes match links"
exit 0
