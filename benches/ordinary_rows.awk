# Random cycles inside the theory over four compliance families (seeded, reproducible):
#   awk -v n=ROWS -v seed=SEED -f benches/ordinary_rows.awk > rows.csv
# Persson, power β = −0.5, Hertz, exponential in turn; P0 = 1, P1 ∈ [0.1, 0.5],
# Q1 ∈ [0.1, 0.6]·f·P1, φ ∈ [0.05π, 0.95π], f ∈ [0.5, 1.2], λ ∈ [1, 2].
BEGIN {
    srand(seed)
    split("persson:gamma=1,sigma=1|power:c=0.5,beta=-0.5|hertz:r=2,estar=3|exp:a=1,c=0.5,d=0.2", spec, "|")
    print "id,p0,p1,q0,q1,phi,friction,lambda,compliance"
    for (i = 0; i < n; i++) {
        f = 0.5 + 0.7 * rand(); p1 = 0.1 + 0.4 * rand(); q1 = (0.1 + 0.5 * rand()) * f * p1
        printf "r%d,1,%.4f,0,%.4f,%.3fpi,%.2f,%.3f,\"%s\"\n", i, p1, q1, 0.05 + 0.9 * rand(), f, 1 + rand(), spec[i % 4 + 1]
    }
}
