#!/usr/bin/env python3
# Prints the functions of the given C++ files that are at least $MIN lines long (default 80):
# "LINES FILE FIRST_LINE", longest first. Brace matching on comment- and string-stripped text;
# lambdas count toward the function that holds them.
import re,sys,glob
def strip(src):
    out=[];i=0;n=len(src)
    while i<n:
        c=src[i]
        if src.startswith('//',i):
            j=src.find('\n',i); j=n if j<0 else j; out.append(' '*(j-i)); i=j
        elif src.startswith('/*',i):
            j=src.find('*/',i)+2; out.append(re.sub(r'[^\n]',' ',src[i:j])); i=j
        elif src.startswith('R"(',i):
            j=src.find(')"',i)+2; out.append(re.sub(r'[^\n]',' ',src[i:j])); i=j
        elif c in '"\'':
            j=i+1
            while j<n and src[j]!=c:
                j+= 2 if src[j]=='\\' else 1
            out.append(c+' '*(j-i-1)+c); i=j+1
        else: out.append(c); i+=1
    return ''.join(out)
res=[]
for f in sys.argv[1:]:
    s=strip(open(f).read())
    stack=[]; # (kind,startline)
    line=1; last=0
    for i,c in enumerate(s):
        if c=='\n': line+=1
        elif c=='{':
            head=s[last:i]
            kind='blk'
            infn=any(k=='fn' for k,_ in stack)
            if not infn and ')' in head and not re.search(r'\b(namespace|struct|class|enum)\b',head.split(';')[-1]) :
                kind='fn'
            stack.append((kind,line)); last=i+1
        elif c=='}':
            k,st=stack.pop(); last=i+1
            if k=='fn':
                res.append((line-st+1,f,st))
        elif c==';': last=i+1
res.sort(reverse=True)
for r in res:
    if r[0]>=int(__import__('os').environ.get('MIN','80')): print(*r)
