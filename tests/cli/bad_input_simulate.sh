# `simulate` rejects bad input with a non-zero exit and a message naming the
# parameter, the value and the allowed range (docs/bad-input.md).
source "$(dirname "$0")/lib.sh"

# non-finite values, for every parameter
for p in m k g mu V lambda ta; do
  expect_fail "--$p|'nan'|finite" simulate --$p nan
  expect_fail "--$p|'inf'|finite" simulate --$p inf
  expect_fail "--$p|'-inf'|finite" simulate --$p=-inf
done
# values <= 0, for every parameter (symbol and long alias)
expect_fail "m (mass)|0|> 0" simulate --m 0
expect_fail "m (mass)|-1|> 0" simulate --mass -1
expect_fail "k (stiffness)|0|> 0" simulate --k 0
expect_fail "k (stiffness)|-4|> 0" simulate --stiffness -4
expect_fail "g (gravity)|0|> 0" simulate --g 0
expect_fail "g (gravity)|-9.81|> 0" simulate --gravity -9.81
expect_fail "mu (friction coefficient)|0|> 0" simulate --mu 0
expect_fail "mu (friction coefficient)|-5|> 0" simulate --friction-coefficient -5
expect_fail "V (belt speed)|0|> 0" simulate --V 0
expect_fail "V (belt speed)|-1|> 0" simulate --belt-speed -1
expect_fail "lambda (switch rate)|0|> 0" simulate --lambda 0
expect_fail "lambda (switch rate)|-2|> 0" simulate --switch-rate -2
expect_fail "ta (window)|0|> 0" simulate --ta 0
expect_fail "ta (window)|-50|> 0" simulate --window -50
# magnitudes the closed form cannot square, alone or in a derived scale
expect_fail "m (mass)|1e+300|between 1e-60 and 1e60" simulate --mu 1e300 --m 1e300
expect_fail "band half-width|e+80|between 1e-60 and 1e60" simulate --mu 1e40 --m 1e40
expect_fail "x0 (initial position)|1e+70|1e60" simulate --x0 1e70
# not a number
expect_fail "--mu|'abc'|not a number" simulate --mu abc
expect_fail "--k|'4x'|trailing" simulate --k 4x
# switch times: unsorted, negative, repeated, non-numeric, non-finite
expect_fail "--switch-times entry #3|1|sorted" simulate --switch-times 0.5,2,1
expect_fail "--switch-times entry #1|-1|>= 0" simulate --switch-times=-1,2
expect_fail "--switch-times entry #2|2|sorted" simulate --switch-times 2,2
expect_fail "--switch-times entry #2|'x'" simulate --switch-times 1,x
expect_fail "--switch-times entry #2|not finite" simulate --switch-times 1,inf
printf '# belt\n1.0\n3.0\n2.0\n' >unsorted.txt
expect_fail "unsorted.txt:4|2|sorted" simulate --switch-times-file unsorted.txt
printf '0.5\n-3\n' >negative.txt
expect_fail "negative.txt:2|-3|>= 0" simulate --switch-times-file negative.txt
expect_fail "missing.txt" simulate --switch-times-file missing.txt
expect_fail "--switch-times" simulate --switch-times 1 --switch-times-file unsorted.txt
# replay inputs
expect_fail "--x0|'nan'|finite" simulate --x0 nan
expect_fail "--xdot0|'1..2'" simulate --xdot0 1..2
expect_fail "--belt-start|'2'|+1 (first level), -1 (second level)" simulate --belt-start 2
# counters
expect_fail "--seed|'-1'" simulate --seed -1
expect_fail "--seed|'1.5'" simulate --seed 1.5
expect_fail "--realization|'-3'" simulate --realization -3
expect_fail "--max-events|'0'" simulate --max-events 0
expect_fail "--trajectory|0|> 0" simulate --trajectory 0
expect_fail "--trajectory|'nan'" simulate --trajectory nan
# the event bound is an error, never a silent truncation
# expected switches over the bound: refused before any work
expect_fail "lambda * ta|5000|max_events / 2 = 5" simulate --lambda 100 --max-events 10
# far more slip reversals than switches (x0 = 1000 m, band 1 mm): stopped at the bound
expect_fail "bound on events|--max-events" simulate --x0 1000 --mu 0.01 --k 100 --max-events 200
# unknown flags and values
expect_fail "--bogus" simulate --bogus 1
expect_fail "--lamda" simulate --lamda 1
expect_fail "--format" simulate --format xml
# a directory is not a switch-times file
expect_fail "not a regular file" simulate --switch-times-file /tmp
finish
