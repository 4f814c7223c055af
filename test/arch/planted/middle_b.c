/* planted: calls middle_a.c, which calls back */
void plantMiddleA(int k);
void plantMiddleB(int k);
void plantMiddleB(int k) { if (k > 0) plantMiddleA(k - 1); }
